// The wavetrace library: load or build a scene, build its BVH, trace rays, write images.
#pragma once

#include "wavetrace/image/image.h"
#include "wavetrace/math/aabb.h"
#include "wavetrace/math/frame.h"
#include "wavetrace/math/ray.h"
#include "wavetrace/math/transform.h"
#include "wavetrace/math/vec3.h"
#include "wavetrace/render/aov.h"
#include "wavetrace/render/film.h"
#include "wavetrace/render/megakernel.h"
#include "wavetrace/render/render.h"
#include "wavetrace/render/sampler.h"
#include "wavetrace/render/wavefront.h"
#include "wavetrace/scene/bvh.h"
#include "wavetrace/scene/intersect.h"
#include "wavetrace/scene/scene.h"
#include "wavetrace/scene/surface.h"
