// Finite-value checks for GLM vectors and matrices (glm's own isfinite is an experimental ext).
#pragma once

#include <cmath>
#include <glm/glm.hpp>

namespace lantern {

template <glm::length_t N, class T, glm::qualifier Q>
bool all_finite(const glm::vec<N, T, Q>& v) {
  for (glm::length_t i = 0; i < N; ++i)
    if (!std::isfinite(v[i])) return false;
  return true;
}

template <glm::length_t C, glm::length_t R, class T, glm::qualifier Q>
bool all_finite(const glm::mat<C, R, T, Q>& m) {
  for (glm::length_t i = 0; i < C; ++i)
    if (!all_finite(m[i])) return false;
  return true;
}

}  // namespace lantern
