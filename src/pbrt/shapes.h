// pbrt-v4's shapes that wavetrace renders as triangle meshes: `trianglemesh` and
// `bilinearmesh` as written, `disk` and `cylinder` tessellated (scene/tessellate.h),
// `loopsubdiv` subdivided (Loop 1987).
#pragma once

#include <string>

#include "pbrt/params.h"
#include "pbrt/translate.h"

namespace wavetrace {

// The mesh of a Shape directive of that type, from its parameters, in the shape's own
// coordinates, its triangles counter-clockwise about pbrt's surface normal (which follows
// the vertex normals N where given). Throws SceneError naming the parameter's place.
PbrtMesh pbrt_shape_mesh(const std::string& type, PbrtParams& p, const std::string& place);

// ReverseOrientation: every triangle wound the other way.
void reverse_winding(PbrtMesh* mesh);

}  // namespace wavetrace
