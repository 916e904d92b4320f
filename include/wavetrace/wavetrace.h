// The wavetrace library: load or build a scene, build its BVH, trace rays, render into a film,
// write images.
#pragma once

#include "wavetrace/accel/bvh.h"
#include "wavetrace/build_info.h"
#include "wavetrace/engines/aov.h"
#include "wavetrace/engines/render.h"
#include "wavetrace/film/film.h"
#include "wavetrace/film/film_file.h"
#include "wavetrace/image/compare.h"
#include "wavetrace/image/image.h"
#include "wavetrace/loaders/load_scene.h"
#include "wavetrace/math/aabb.h"
#include "wavetrace/math/frame.h"
#include "wavetrace/math/ray.h"
#include "wavetrace/math/transform.h"
#include "wavetrace/math/vec3.h"
#include "wavetrace/scene/scene.h"
#include "wavetrace/shading/estimator.h"
#include "wavetrace/shading/surface.h"
