#pragma once

#include <optional>

#include "wavetrace/math/frame.h"
#include "wavetrace/math/vec3.h"
#include "wavetrace/scene/ids.h"

namespace wavetrace {

// What rays that leave the scene see: a constant radiance, or an environment image scaled by
// `radiance`, in one of two mappings of the sphere of directions (docs/scene-format.md):
// - LatLong: equirectangular. With +y up, u = 0.5 + (atan2(d.x, -d.z) - rotation) / (2 pi)
//   (so -z is the image centre at rotation 0), v = acos(d.y) / pi with v = 0 the top row
//   (straight up); looked up bilinearly.
// - EqualArea: pbrt-v4's square equal-area octahedral map (src/math/equal_area.h): +z at the
//   image centre, -z at its corners, every texel the same solid angle; looked up at the nearest
//   texel, as pbrt-v4 does.
// Directions are taken into the map's own frame first when `frame` is set.
struct Background {
    enum class Kind : uint8_t { Constant, Environment };
    enum class Mapping : uint8_t { LatLong, EqualArea };
    Kind kind = Kind::Constant;
    Color radiance{0.0f};  // Constant: the radiance. Environment: a per-channel scale.
    ImageId image = kNone;
    Mapping mapping = Mapping::LatLong;
    float rotation = 0.0f;  // LatLong: rotation about the map's +y, degrees
    // LatLong: where the image's rows lie. False: row j of H at v = (j + 0.5) / H, each row
    // the centre of its band (pbrt's, Tungsten's). True: at v = j / (H - 1), the first and last
    // rows on the poles (Mitsuba 3's envmap). Columns are centred either way.
    bool rows_at_poles = false;
    // The map's own x, y and z axes in world space (a rotation, possibly mirrored): a world
    // direction d is looked up as frame->to_local(d). None: the map's axes are the world's.
    std::optional<Frame> frame;

    bool is_black() const {
        return kind == Kind::Constant && radiance.x == 0 && radiance.y == 0 && radiance.z == 0;
    }
};

struct Scene;
// Radiance arriving along direction d (d need not be unit length) from the background.
Color eval_background(const Scene& scene, Vec3 d);

// The environment's mapping and its inverse: unit direction <-> (u, row) in [0,1)^2, with row 0
// the top of the image. The solid angle per unit of (u, row) is 2 pi^2 sin(theta) for LatLong
// (theta = pi row), 4 pi for EqualArea: environment_jacobian(bg, row).
Vec2 environment_uv(const Background& bg, Vec3 unit_dir);
Vec3 environment_direction(const Background& bg, float u, float row);
float environment_jacobian(const Background& bg, float row);

struct ImageData;
// The illuminance that environment image `image`, in bg's mapping and at unit scale, casts on
// a surface facing the map's pole (+z of an equal-area map, +y of a lat-long one: its top row),
// in the map's own frame: E = integral over the upper hemisphere of Y(L) cos(theta) d omega,
// Y the Rec. 709 luminance, as the Riemann sum over texel centres (each texel's solid angle
// from the mapping's Jacobian). Scenes scale a map by E_target / E to meet an illuminance.
double environment_illuminance(const Background& bg, const ImageData& image);

}  // namespace wavetrace
