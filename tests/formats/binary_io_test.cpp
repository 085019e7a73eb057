// Binary files in memory: FNV-1a 64 against published test vectors, writer →
// reader round trip, reads past the end refused naming the file, checksums.
#include <catch2/catch.hpp>

#include "src/formats/binary_io.h"
#include "src/core/math.h"

using namespace rsl;

TEST_CASE("FNV-1a 64 matches the reference test vectors and chains", "[binary_io]") {
    CHECK(fnv1a64("", 0) == 0xcbf29ce484222325ull);
    CHECK(fnv1a64("a", 1) == 0xaf63dc4c8601ec8cull);
    CHECK(fnv1a64("foobar", 6) == 0x85944171f73967e8ull);
    CHECK(fnv1a64("bar", 3, fnv1a64("foo", 3)) == fnv1a64("foobar", 6));
}

TEST_CASE("BinaryWriter and BinaryReader round trip, short reads name the file", "[binary_io]") {
    BinaryWriter w;
    w.put(uint32_t(0xdeadbeef));
    w.put(Vec3(1.5f, -2, 3));
    w.put_string("hello");
    const float table[3] = {0.25f, 1e-30f, -7};
    w.put_bytes(table, sizeof(table));
    const std::string bytes = w.finish_with_checksum();
    REQUIRE(bytes.size() == 4 + 12 + 4 + 5 + 12 + 8);
    CHECK(has_valid_checksum(bytes));
    CHECK(stored_checksum(bytes) == fnv1a64(bytes.data(), bytes.size() - 8));

    BinaryReader r("some.bin", bytes, bytes.size() - 8);
    CHECK(r.get<uint32_t>() == 0xdeadbeef);
    CHECK(r.get<Vec3>() == Vec3(1.5f, -2, 3));
    CHECK(r.get_string("name") == "hello");
    float back[3];
    r.get_bytes(back, sizeof(back));
    CHECK((back[0] == 0.25f && back[1] == 1e-30f && back[2] == -7));
    CHECK(r.remaining() == 0);
    CHECK(r.position() == bytes.size() - 8);
    CHECK_THROWS_WITH(r.get<uint8_t>("flag"), "some.bin: truncated or corrupt: the file ends inside the flag");

    // A string whose length runs past the end is refused before it is copied.
    BinaryWriter lying;
    lying.put(uint32_t(1000));
    lying.put_bytes("abc", 3);
    BinaryReader short_reader("lying.bin", lying.bytes(), lying.bytes().size());
    CHECK_THROWS_WITH(short_reader.get_string("part name"), Catch::StartsWith("lying.bin: truncated or corrupt"));

    // Any flipped bit breaks the checksum; too short a file has none.
    for (size_t i = 0; i < bytes.size(); ++i) {
        std::string flipped = bytes;
        flipped[i] ^= char(1 << (i % 8));
        CHECK_FALSE(has_valid_checksum(flipped));
    }
    CHECK_FALSE(has_valid_checksum("1234567"));
}
