// A film as Python holds it: the per-pixel sums with what they are of (FilmPart).
#pragma once

#include "wavetrace/film/film_file.h"

namespace wavetrace::python {

// A film that has no settings yet takes those of the first render into it.
using PyFilm = FilmPart;

inline bool is_fresh(const PyFilm& f) {
    return f.info.settings.empty();
}

}  // namespace wavetrace::python
