#include "math/equal_area.h"

#include "math/equal_area-inl.h"

namespace wavetrace {
namespace lanes = HWY_NAMESPACE;
using lanes::OneLane;

Vec3 equal_area_square_to_sphere(float u, float v) {
    return lanes::to_vec3(lanes::EqualAreaSquareToSphere<OneLane>(u, v));
}

Vec2 equal_area_sphere_to_square(Vec3 d) {
    Vec2 uv;
    lanes::EqualAreaSphereToSquare<OneLane>(lanes::to_lanes(d), &uv.x, &uv.y);
    return uv;
}

}  // namespace wavetrace
