#pragma once
// The two exceptions rsl throws, shared by the library's internals
// (src/core/error.h adds the helpers that throw them) and its public API
// (<rsl/rsl.h>), so that a caller catches exactly what the `rsl` program
// reports:
//   rsl::Error          bad input; what() is the message `rsl` prints after
//                       "rsl: error: " (it names the file and the problem).
//   rsl::InternalError  a broken invariant, i.e. a bug in rsl ("rsl: internal
//                       error: …", exit status 2).
#include <stdexcept>

namespace rsl {

class Error : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

class InternalError : public std::logic_error {
public:
    using std::logic_error::logic_error;
};

}  // namespace rsl
