#include <shade/shade.hpp>

double odr_b_frame_sum() {
    const auto f = shade::frame<double>::from_normal({0.0, 0.0, 1.0});
    return f.t.x + f.b.y + f.n.z;
}
