// Catch's main, plus an exit code that tells CTest a run skipped: 77 when a
// case warned "SKIPPED:" and nothing failed, 1 when anything failed, so a
// skipping case can never hide a failing one in the same ctest test.
#define CATCH_CONFIG_RUNNER
#include <catch2/catch.hpp>

#include <string>

#include "skip_exit_code.h"

namespace {

bool g_ran_a_case = false;
bool g_skipped = false;

struct SkipListener : Catch::TestEventListenerBase {
    using TestEventListenerBase::TestEventListenerBase;

    void testCaseStarting(Catch::TestCaseInfo const& info) override {
        g_ran_a_case = true;
        TestEventListenerBase::testCaseStarting(info);
    }

    bool assertionEnded(Catch::AssertionStats const& stats) override {
        const Catch::AssertionResult& result = stats.assertionResult;
        if (result.getResultType() == Catch::ResultWas::Warning &&
            result.getMessage().rfind("SKIPPED:", 0) == 0)
            g_skipped = true;
        return TestEventListenerBase::assertionEnded(stats);
    }
};

}  // namespace

CATCH_REGISTER_LISTENER(SkipListener)

int main(int argc, char* argv[]) {
    const int result = Catch::Session().run(argc, argv);
    // Listing (catch_discover_tests counts the cases from it) keeps Catch's own code.
    if (!g_ran_a_case)
        return result;
    if (result != 0)
        return 1;
    return g_skipped ? rsl_test::kSkipExitCode : 0;
}
