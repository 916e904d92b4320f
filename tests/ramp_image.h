// A grey test image whose texel (x, y) (y the row from the top) holds x + 10 y, so that a
// looked-up value names the texel it came from (exact in EXR's floats).
#pragma once

#include "wavetrace/image/image.h"

namespace wavetrace {

inline Image ramp_image(int width, int height) {
    Image img(width, height);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) img.at(x, y) = Color(static_cast<float>(x + 10 * y));
    return img;
}

}  // namespace wavetrace
