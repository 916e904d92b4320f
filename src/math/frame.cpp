#include "wavetrace/math/frame.h"

#include "math/lanes-inl.h"

namespace wavetrace {

Frame Frame::from_normal(Vec3 n) {
    namespace lanes = HWY_NAMESPACE;
    lanes::V3<float> s, t;
    lanes::OrthonormalBasis<lanes::OneLane>(lanes::to_lanes(n), &s, &t);
    return {lanes::to_vec3(s), lanes::to_vec3(t), n};
}

}  // namespace wavetrace
