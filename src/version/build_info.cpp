#include "src/version/build_info.h"

#include <embree3/rtcore.h>
#include <OpenEXR/OpenEXRConfig.h>
#include <OpenEXR/openexr_base.h>
#include <fmt/format.h>

#include "rsl/version.h"

namespace rsl {
namespace {

// The Embree library that is loaded (its device reports it) and the one the
// headers came from; they differ when the shared library was upgraded.
std::string embree_version() {
    std::string loaded = "unavailable";
    if (RTCDevice device = rtcNewDevice("verbose=0")) {
        const ssize_t v = rtcGetDeviceProperty(device, RTC_DEVICE_PROPERTY_VERSION);
        loaded = fmt::format("{}.{}.{}", v / 10000, v / 100 % 100, v % 100);
        rtcReleaseDevice(device);
    }
    return fmt::format("{} (built against {})", loaded, RTC_VERSION_STRING);
}

std::string openexr_version() {
    int major = 0, minor = 0, patch = 0;
    const char* extra = nullptr;
    exr_get_library_version(&major, &minor, &patch, &extra);
    return fmt::format("{}.{}.{}{} (built against {})", major, minor, patch, extra ? extra : "", OPENEXR_VERSION_STRING);
}

}  // namespace

BuildInfo build_info() {
    BuildInfo info;
    info.version = RSL_VERSION_STRING;
    info.commit = build_commit();
    info.build_type = build_type();
    info.embree = embree_version();
    info.openexr = openexr_version();
    return info;
}

std::string build_info_text() {
    const BuildInfo info = build_info();
    return fmt::format("rsl {}\ncommit: {}\nbuild type: {}\nEmbree: {}\nOpenEXR: {}\n", info.version, info.commit,
                       info.build_type, info.embree, info.openexr);
}

}  // namespace rsl
