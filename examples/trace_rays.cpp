// The README's library example: build a scene in code, build its BVH, trace a ray.
#include <cstdio>

#include "wavetrace/wavetrace.h"

int main() {
    using namespace wavetrace;
    Scene scene;
    MaterialId white = scene.add_material({.name = "white",
                                           .kind = MaterialKind::Lambertian,
                                           .albedo = scene.add_solid({0.73f, 0.73f, 0.73f})});
    scene.add_sphere({.center = {0, 1, 0}, .radius = 1, .material = white});
    scene.add_box({-5, -1, -5}, {5, 0, 5}, white, kNone);  // a floor slab

    Bvh bvh = Bvh::build(scene);
    Ray ray{.o = {0, 1, -10}, .d = {0, 0, 1}};
    Hit hit = bvh.intersect(ray);
    if (!hit.found()) return 1;
    SurfaceHit s = surface_at(scene, ray, hit);
    std::printf("hit at t = %g, point (%g %g %g), normal (%g %g %g)\n", hit.t, s.p.x, s.p.y, s.p.z,
                s.ng.x, s.ng.y, s.ng.z);
    return bvh.occluded({.o = {0, 5, 0}, .d = {0, -1, 0}}) ? 0 : 1;
}
