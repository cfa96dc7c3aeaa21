// Two translation units that include the umbrella header and use the same templates; a
// non-inline definition with external linkage in a header would make this fail to link.
#include <shade/shade.hpp>

double odr_b_frame_sum();

int main() {
    const auto f = shade::frame<double>::from_normal({0.0, 0.0, 1.0});
    const double here = f.t.x + f.b.y + f.n.z;
    return here == odr_b_frame_sum() ? 0 : 1;
}
