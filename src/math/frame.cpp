#include "wavetrace/math/frame.h"

#include <cmath>

#include "math/lanes-inl.h"

namespace wavetrace {

Frame Frame::from_normal(Vec3 n) {
    namespace lanes = HWY_NAMESPACE;
    lanes::V3<float> s, t;
    lanes::OrthonormalBasis<lanes::OneLane>(lanes::to_lanes(n), &s, &t);
    return {lanes::to_vec3(s), lanes::to_vec3(t), n};
}

bool Frame::is_orthonormal(float tolerance) const {
    const Vec3 axes[3] = {s, t, n};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            if (!(std::abs(dot(axes[i], axes[j]) - (i == j ? 1.0f : 0.0f)) <= tolerance))
                return false;
    return true;
}

}  // namespace wavetrace
