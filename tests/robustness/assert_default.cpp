// SHADE_ASSERT's default definition (the standard assert): `assert_default bad` passes u
// outside [0,1)^2 to square_to_cosine_hemisphere. Built without NDEBUG it must abort (the
// CTest test expects failure); built with NDEBUG the check is compiled out and the program
// returns 0. `assert_default good` returns 0 in both builds.
#include <cstdio>
#include <cstring>

#include <shade/core/sampling.hpp>

int main(int argc, char** argv) {
    const bool bad = argc > 1 && std::strcmp(argv[1], "bad") == 0;
    const shade::vec2<double> u = bad ? shade::vec2<double>(1.5, 0.5) : shade::vec2<double>(0.25, 0.5);
    const shade::vec3<double> w = shade::square_to_cosine_hemisphere(u);
    std::printf("(%g, %g, %g)\n", w.x, w.y, w.z);
    return 0;
}
