// Cases for tests/ctest_skip_check.cmake: a tag holding a failing and a
// skipping case, a tag that only skips and a tag that only passes.
#include <catch2/catch.hpp>

TEST_CASE("probe: a case that fails", "[mixed]") {
    CHECK(1 + 1 == 3);
}

TEST_CASE("probe: a case that skips beside it", "[mixed][skip-only]") {
    WARN("SKIPPED: the probe's skip");
}

TEST_CASE("probe: a case that passes", "[pass-only]") {
    CHECK(1 + 1 == 2);
}
