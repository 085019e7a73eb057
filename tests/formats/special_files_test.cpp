// Issue 43, "nothing hangs": every reader of a user's file refuses a FIFO, a
// device or a directory at once, naming it and what it is, and refuses a
// file larger than its format allows before reading it (sparse files made
// with a hole stand for the multi-gigabyte ones).
#include <catch2/catch.hpp>

#include <chrono>

#include "src/core/envmap.h"
#include "src/formats/file_reading.h"
#include "src/formats/image_file.h"
#include "src/formats/json_file.h"
#include "src/core/mesh.h"
#include "src/core/scene.h"
#include "src/formats/obj_loader.h"
#include "src/formats/scene_environment.h"
#include "src/formats/scene_file.h"
#include "tests/hostile_inputs.h"
#include "tests/special_files.h"
#include "tests/test_support.h"

using namespace rsl;
using namespace rsl::test;
namespace fs = std::filesystem;

namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

TEST_CASE("Every reader refuses a FIFO at once, naming it and what it is", "[bad-input][special-files]") {
    const fs::path dir = scratch_dir("special_fifo");
    for (const char* name : {"scene.json", "mesh.obj", "sky.hdr", "sky.exr", "model.gltf", "data.json"}) {
        const fs::path fifo = make_fifo(dir / name);
        const FifoRelease release(fifo);
        const auto start = std::chrono::steady_clock::now();
        std::string error;
        if (fifo.extension() == ".obj") error = error_of([&] { load_obj(fifo); });
        else if (fifo.extension() == ".hdr" || fifo.extension() == ".exr") error = error_of([&] { read_hdr_image(fifo); });
        else if (fifo.filename() == "data.json") error = error_of([&] { read_json_file(fifo); });
        else error = error_of([&] { load_scene(fifo); });
        INFO(name << ": " << error);
        CHECK(error == fifo.string() + ": is a FIFO (named pipe), not a regular file");
        CHECK(seconds_since(start) < 2);  // not released by FifoRelease after 5 s
    }
}

TEST_CASE("A glTF buffer or image whose uri names a FIFO is refused at once, naming it", "[bad-input][special-files]") {
    // Issue 56: tinygltf's own FileExists opened the FIFO and waited for a writer forever.
    const fs::path dir = scratch_dir("special_fifo_gltf");
    const fs::path fifo = make_fifo(dir / "buffer.bin");
    const FifoRelease release(fifo);
    write_text(dir / "model.gltf", hostile::gltf_triangle("3", "buffer.bin"));
    const auto start = std::chrono::steady_clock::now();
    const std::string error = error_of([&] { load_scene(dir / "model.gltf"); });
    INFO(error);
    CHECK(error.find((dir / "model.gltf").string() + ": ") == 0);
    CHECK(error.find("buffer.bin: is a FIFO (named pipe), not a regular file") != std::string::npos);
    CHECK(seconds_since(start) < 2);

    // A base colour image: the reader's reason, where the material said "could not be read (missing file?)".
    const fs::path image = make_fifo(dir / "img.png");
    const FifoRelease image_release(image);
    std::string textured = hostile::gltf_triangle();
    const std::string attributes = R"("attributes": {"POSITION": 0}})";
    textured.replace(textured.find(attributes), attributes.size(),
                     R"("attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "material": 0})");
    const std::string accessor = R"("type": "VEC3"})";
    textured.replace(textured.find(accessor), accessor.size(),
                     R"("type": "VEC3"}, {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC2"})");
    textured.insert(textured.rfind('}'), R"(, "materials": [{"name": "painted", "pbrMetallicRoughness":
  {"baseColorTexture": {"index": 0}}}], "textures": [{"source": 0}], "images": [{"uri": "img.png"}])");
    write_text(dir / "textured.gltf", textured);
    const auto image_start = std::chrono::steady_clock::now();
    const std::string image_error = error_of([&] { load_scene(dir / "textured.gltf"); });
    INFO(image_error);
    CHECK(image_error.find((dir / "textured.gltf").string() + ": ") == 0);
    CHECK(image_error.find("base colour image 'img.png': " + image.string() +
                           ": is a FIFO (named pipe), not a regular file") != std::string::npos);
    CHECK(seconds_since(image_start) < 2);
}

TEST_CASE("Readers refuse a directory, a character device and a link to /dev/zero", "[bad-input][special-files]") {
    const fs::path dir = scratch_dir("special_devices");
    const fs::path folder = make_directory(dir / "folder.json");
    CHECK(error_of([&] { load_scene(folder); }) == folder.string() + ": is a directory, not a regular file");
    CHECK(error_of([&] { load_obj("/dev/null"); }) == "/dev/null: is a character device, not a regular file");
    // Before the fix the scene reader read /dev/zero until memory ran out (2 GB in 15 s).
    const fs::path zero = make_dev_zero_link(dir / "zero.json");
    const auto start = std::chrono::steady_clock::now();
    CHECK(error_of([&] { load_scene(zero); }) == zero.string() + ": is a character device, not a regular file");
    CHECK(error_of([&] { read_hdr_image(make_dev_zero_link(dir / "zero.hdr")); }).find("is a character device") !=
          std::string::npos);
    CHECK(seconds_since(start) < 2);
}

TEST_CASE("A scene file names the key of a file that is not a regular file, and what it is",
          "[bad-input][special-files]") {
    const fs::path dir = scratch_dir("special_scene_keys");
    make_fifo(dir / "pipe.obj");
    make_directory(dir / "folder.obj");
    write_text(dir / "scene.json", R"({"parts": [{"obj": "pipe.obj"}]})");
    CHECK(error_of([&] { load_scene(dir / "scene.json"); }) ==
          fmt::format("{}: parts[0].obj: file {} is a FIFO (named pipe), not a regular file", (dir / "scene.json").string(),
                      (dir / "pipe.obj").string()));
    write_text(dir / "scene.json", R"({"parts": [{"obj": "folder.obj"}]})");
    CHECK(error_of([&] { load_scene(dir / "scene.json"); }).find("parts[0].obj: file " + (dir / "folder.obj").string() +
                                                                 " is a directory, not a regular file") != std::string::npos);
    write_text(dir / "scene.json", R"({"parts": [{"obj": "missing.obj"}]})");
    CHECK(error_of([&] { load_scene(dir / "scene.json"); }).find("missing.obj does not exist") != std::string::npos);
}

TEST_CASE("Files larger than their format allows are refused with their size and the limit, unread",
          "[bad-input][special-files]") {
    const fs::path dir = scratch_dir("special_sizes");
    const auto start = std::chrono::steady_clock::now();
    // A scene file one byte past the limit.
    const fs::path json = make_sparse_file(dir / "big.json", kMaxJsonFileBytes + 1, "{");
    CHECK(error_of([&] { load_scene(json); }) ==
          fmt::format("{}: is {} bytes; a JSON file may be at most {} bytes (64 MiB)", json.string(),
                      kMaxJsonFileBytes + 1, kMaxJsonFileBytes));
    // An OBJ past its limit is refused by its size; a smaller sparse one at its first NUL byte.
    const fs::path huge_obj = make_sparse_file(dir / "huge.obj", kMaxObjFileBytes + 1, "v 0 0 0\n");
    CHECK(error_of([&] { load_obj(huge_obj); }).find(fmt::format("is {} bytes; an OBJ file may be at most {} bytes",
                                                                 kMaxObjFileBytes + 1, kMaxObjFileBytes)) != std::string::npos);
    const fs::path sparse_obj = make_sparse_file(dir / "sparse.obj", uintmax_t(2) << 30, "v 0 0 0\n");
    CHECK(error_of([&] { load_obj(sparse_obj); }) ==
          sparse_obj.string() + ": contains NUL bytes (the first at byte 8): not a text OBJ file");
    // A Radiance file: the magic number, then the size.
    const fs::path hdr = make_sparse_file(dir / "huge.hdr", kMaxRadianceFileBytes + 1, "#?RADIANCE\n");
    CHECK(error_of([&] { read_hdr_image(hdr); }).find("a Radiance HDR file may be at most") != std::string::npos);
    CHECK(seconds_since(start) < 5);  // before the fix: tens of seconds and gigabytes for each
}

TEST_CASE("read_bounded_file checks the magic number before the size, and reads a file at its limit",
          "[special-files]") {
    const fs::path dir = scratch_dir("special_bounded");
    const fs::path huge = make_sparse_file(dir / "huge.bin", uintmax_t(100) << 30);
    CHECK(error_of([&] { read_bounded_file(huge, 1024, "a test file", "MAGIC", "wrong magic"); }) ==
          huge.string() + ": wrong magic");
    write_text(dir / "exact.bin", "MAGIC" + std::string(1019, 'x'));
    CHECK(read_bounded_file(dir / "exact.bin", 1024, "a test file", "MAGIC", "wrong magic").size() == 1024);
    CHECK(error_of([&] { read_bounded_file(dir / "exact.bin", 1023, "a test file"); }) ==
          (dir / "exact.bin").string() + ": is 1024 bytes; a test file may be at most 1023 bytes");
    CHECK(error_of([&] { read_bounded_file(dir / "absent.bin", 1024, "a test file"); }) ==
          (dir / "absent.bin").string() + ": does not exist");
    CHECK(why_not_regular_file(dir / "exact.bin").empty());
}

TEST_CASE("An environment map's error names the scene file and its key, as a mesh's does", "[bad-input][special-files]") {
    const fs::path dir = scratch_dir("special_envmap");
    write_text(dir / "box.obj", kUnitBoxObj);
    write_text(dir / "sky.hdr", "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 4 +X 8\n");  // no pixels
    write_text(dir / "scene.json", R"({"parts": [{"obj": "box.obj"}], "environment": {"file": "sky.hdr"}})");
    const Scene scene = load_scene(dir / "scene.json");
    const std::string error = error_of([&] { scene_environment_map(scene, 8); });
    INFO(error);
    CHECK(error.rfind(fmt::format("{}: environment.file: {}: ", (dir / "scene.json").string(), (dir / "sky.hdr").string()), 0) == 0);
}
