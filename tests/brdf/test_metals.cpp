#include <cmath>

#include <doctest/doctest.h>

#include <shade/brdf/cook_torrance.hpp>
#include <shade/brdf/metals.hpp>

#include "brdf/support.hpp"

using namespace brdf_test;

namespace {

// Reflectance at normal incidence of eta + i kappa: ((eta - 1)^2 + kappa^2)/((eta + 1)^2 + kappa^2)
// (see test_fresnel.cpp), worked out by hand for the tabulated values:
//   gold      (0.14 + 3.697i, 0.43 + 2.455i, 1.38 + 1.914i)    -> 0.962585, 0.786916, 0.408220
//   silver    (0.05 + 4.483i, 0.06 + 3.586i, 0.04 + 2.657i)    -> 0.990566, 0.982836, 0.980347
//   copper    (0.22 + 3.747i, 1.02 + 2.577i, 1.24 + 2.397i)    -> 0.943330, 0.619450, 0.539171
//   aluminium (1.4665 + 7.5603i, 0.9596 + 6.4430i, 0.5925 + 5.3215i) -> 0.907245, 0.915365, 0.923188
template <class T>
void check_f0(const shade::conductor_fresnel<T>& metal, const rgb<T>& expected) {
    CHECK(close(metal.f0(), expected, T(2e-6)));
}

} // namespace

TEST_CASE_TEMPLATE("metals: reflectance at normal incidence from the tabulated indices", T, float, double) {
    check_f0(shade::metals::gold<T>(), rgb<T>(T(0.9625853746630428), T(0.7869157604908371), T(0.4082203341496748)));
    check_f0(shade::metals::silver<T>(), rgb<T>(T(0.9905659438402902), T(0.9828362963130362), T(0.9803469958970669)));
    check_f0(shade::metals::copper<T>(), rgb<T>(T(0.9433296740187613), T(0.6194501633146412), T(0.5391708922496998)));
    check_f0(shade::metals::aluminium<T>(), rgb<T>(T(0.9072448307261913), T(0.9153647864710848), T(0.9231876627329729)));
}

TEST_CASE_TEMPLATE("metals: valid for the validating constructor, hue as measured", T, float, double) {
    for (const auto& metal : {shade::metals::gold<T>(), shade::metals::silver<T>(), shade::metals::copper<T>(),
                              shade::metals::aluminium<T>()}) {
        CHECK_NOTHROW((void)shade::conductor_fresnel<T>(metal.eta(), metal.kappa()));
        // F rises to 1 at grazing in every channel.
        CHECK(close(metal.F(T(0)), rgb<T>(1), T(1e-5)));
    }
    // Gold and copper reflect red best and blue least.
    const rgb<T> gold = shade::metals::gold<T>().f0(), copper = shade::metals::copper<T>().f0();
    CHECK(gold.x > gold.y);
    CHECK(gold.y > gold.z);
    CHECK(copper.x > copper.y);
    CHECK(copper.y > copper.z);
}

TEST_CASE_TEMPLATE("metals: a gold cook_torrance evaluates and samples", T, float, double) {
    using model = shade::cook_torrance<shade::ggx<T>, shade::conductor_fresnel<T>, shade::smith_height_correlated<T>>;
    static_assert(shade::sampled_brdf<model>);
    const model gold(shade::ggx<T>(T(0.25)), shade::metals::gold<T>());
    const auto at = tilted<T>();
    // l = v = n: F = f0, D = 1/(pi 0.0625) = 16/pi, G2 = 1: f = f0 16/(4 pi) = 4 f0/pi.
    CHECK(close(gold.f(at.n(), at.n(), at), shade::metals::gold<T>().f0() * (T(4) / shade::pi<T>), T(1e-5)));
    const auto s = gold.sample(direction(at, T(0.7), T(0.2)), T(0.5), shade::vec2<T>(T(0.3), T(0.8)), at);
    REQUIRE(s);
    CHECK(finite_non_negative(s->weight));
    check_finite_non_negative(gold, at);
}
