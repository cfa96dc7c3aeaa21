#include "support/float_literals.hpp"

#include <string_view>

namespace shade::examples {

void write_float_literals(std::FILE* f, const float* x, std::size_t count, int digits) {
    for (std::size_t i = 0; i < count; ++i) {
        char text[32];
        std::snprintf(text, sizeof text, "%.*g", digits, double(x[i]));
        const bool has_point = std::string_view(text).find_first_of(".e") != std::string_view::npos;
        std::fprintf(f, "%s%s%sf", i ? ", " : "", text, has_point ? "" : ".");
    }
}

} // namespace shade::examples
