// Colour helpers shared by GPU and CPU: the scalar luminance ReSTIR target functions resample by.
#ifndef LANTERN_SHARED_COLOR_H
#define LANTERN_SHARED_COLOR_H

#include "shared/lang.h"

LANTERN_BEGIN_SHARED

// Relative luminance of linear Rec.709/sRGB primaries (the working space of the renderer).
LANTERN_FUNC float luminance(vec3 rgb) {
  return dot(rgb, vec3(0.2126f, 0.7152f, 0.0722f));
}

LANTERN_END_SHARED

#endif
