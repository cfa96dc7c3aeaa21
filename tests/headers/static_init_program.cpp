// A program with a namespace-scope variable initialised at run time, as an inline
// variable in a header would be: the static initialiser check must find its
// _GLOBAL__sub_I_ function (tests/headers/no_static_init.cmake).
#include <cstdlib>

namespace {
const bool has_home = std::getenv("HOME") != nullptr;
}

int main() { return has_home ? 0 : 1; }
