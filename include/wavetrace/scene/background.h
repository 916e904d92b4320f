#pragma once

#include "wavetrace/math/vec3.h"
#include "wavetrace/scene/ids.h"

namespace wavetrace {

// What rays that leave the scene see: a constant radiance, or an equirectangular
// (latitude-longitude) environment image scaled by `radiance`.
// Mapping, with +y up: u = 0.5 + atan2(d.x, -d.z) / (2 pi) (so -z is the image centre),
// v = acos(d.y) / pi with v = 0 the top row (straight up).
struct Background {
    enum class Kind : uint8_t { Constant, Environment };
    Kind kind = Kind::Constant;
    Color radiance{0.0f};  // Constant: the radiance. Environment: a per-channel scale.
    ImageId image = kNone;
    float rotation = 0.0f;  // Environment: rotation about +y, degrees
    // Environment: where the image's rows lie. False: row j of H at v = (j + 0.5) / H, each row
    // the centre of its band (pbrt's, Tungsten's). True: at v = j / (H - 1), the first and last
    // rows on the poles (Mitsuba 3's envmap). Columns are centred either way.
    bool rows_at_poles = false;

    bool is_black() const {
        return kind == Kind::Constant && radiance.x == 0 && radiance.y == 0 && radiance.z == 0;
    }
};

struct Scene;
// Radiance arriving along direction d (d need not be unit length) from the background.
Color eval_background(const Scene& scene, Vec3 d);

// The environment mapping and its inverse: unit direction <-> (u, row) in [0,1)^2, with row 0
// the top of the image (straight up). The Jacobian is d(omega) = 2 pi^2 sin(theta) du drow.
Vec2 environment_uv(const Background& bg, Vec3 unit_dir);
Vec3 environment_direction(const Background& bg, float u, float row);

}  // namespace wavetrace
