// animation.cpp - a sampler's value at a moment: keys found, then held, interpolated, slerped or splined.
#include "facet/animation.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <string>

#include "facet/error.hpp"

namespace facet {

namespace {

std::string seconds(float t) {
  char text[32];
  std::snprintf(text, sizeof text, "%g s", static_cast<double>(t));
  return text;
}

}  // namespace

float Animation::duration() const {
  float last = 0.0f;
  for (const AnimationSampler& s : samplers)
    if (!s.times.empty()) last = std::max(last, s.times.back());
  return last;
}

void validate(const AnimationSampler& sampler, const std::string& what, const std::string& source) {
  const std::size_t keys = sampler.times.size();
  if (keys == 0) throw InputError(source, what + " has no keys");
  if (sampler.width == 0) throw InputError(source, what + " has keys of no values");
  for (std::size_t k = 0; k < keys; ++k) {
    if (!std::isfinite(sampler.times[k]))
      throw InputError(source, what + ": key " + std::to_string(k) + "'s time is not a finite number");
    if (k > 0 && !(sampler.times[k] > sampler.times[k - 1]))
      throw InputError(source, what + ": key times do not increase (key " + std::to_string(k) + " at " +
                                   seconds(sampler.times[k]) + " after " + seconds(sampler.times[k - 1]) + ")");
  }
  const std::size_t per_key = sampler.width * (sampler.interpolation == Interpolation::cubic_spline ? 3 : 1);
  if (sampler.values.size() != keys * per_key)
    throw InputError(source, what + " has " + std::to_string(sampler.values.size()) + " values for " +
                                 std::to_string(keys) + " keys of " + std::to_string(per_key));
  for (std::size_t i = 0; i < sampler.values.size(); ++i)
    if (!std::isfinite(sampler.values[i]))
      throw InputError(source, what + ": value " + std::to_string(i) + " is not a finite number");
}

namespace {

void normalise(std::span<float> q) {
  float length = 0.0f;
  for (float v : q) length += v * v;
  length = std::sqrt(length);
  if (length > 0.0f)
    for (float& v : q) v /= length;
}

// Spherical linear interpolation of unit quaternions a to b by u, along the shorter arc (b negated when the two lie
// in opposite hemispheres); nearly equal ones are interpolated linearly and normalised, where slerp divides by ~0.
void slerp(const float* a, const float* b, float u, std::span<float> out) {
  float dot = a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3];
  const float sign = dot < 0.0f ? -1.0f : 1.0f;
  dot *= sign;
  float wa = 1.0f - u, wb = u;
  if (dot < 0.9995f) {
    const float angle = std::acos(std::min(dot, 1.0f));
    const float s = std::sin(angle);
    wa = std::sin((1.0f - u) * angle) / s;
    wb = std::sin(u * angle) / s;
  }
  for (int c = 0; c < 4; ++c) out[static_cast<std::size_t>(c)] = wa * a[c] + wb * sign * b[c];
  normalise(out);
}

}  // namespace

void sample(const AnimationSampler& s, float seconds, bool rotation, std::span<float> out) {
  const std::size_t w = s.width, keys = s.times.size();
  const bool cubic = s.interpolation == Interpolation::cubic_spline;
  // A key's value: a cubic spline's keys hold in-tangent, value, out-tangent.
  const auto value = [&](std::size_t k) { return s.values.data() + (cubic ? (3 * k + 1) * w : k * w); };
  const auto hold = [&](std::size_t k) { std::copy_n(value(k), w, out.begin()); };
  if (keys == 1 || !(seconds > s.times.front())) return hold(0);
  if (seconds >= s.times.back()) return hold(keys - 1);
  // The key at or before `seconds`, and the next.
  const std::size_t k =
      static_cast<std::size_t>(std::upper_bound(s.times.begin(), s.times.end(), seconds) - s.times.begin()) - 1;
  const float dt = s.times[k + 1] - s.times[k];
  const float u = (seconds - s.times[k]) / dt;
  switch (s.interpolation) {
    case Interpolation::step: return hold(k);
    case Interpolation::linear:
      if (rotation && w == 4) return slerp(value(k), value(k + 1), u, out);
      for (std::size_t c = 0; c < w; ++c) out[c] = (1.0f - u) * value(k)[c] + u * value(k + 1)[c];
      return;
    case Interpolation::cubic_spline: {
      // glTF's Hermite spline: p0 + m0 (the out-tangent of key k) and p1 + m1 (the in-tangent of key k + 1), the
      // tangents scaled by the keys' spacing.
      const float u2 = u * u, u3 = u2 * u;
      const float h00 = 2 * u3 - 3 * u2 + 1, h10 = u3 - 2 * u2 + u, h01 = -2 * u3 + 3 * u2, h11 = u3 - u2;
      const float* out_tangent = s.values.data() + (3 * k + 2) * w;
      const float* in_tangent = s.values.data() + 3 * (k + 1) * w;
      for (std::size_t c = 0; c < w; ++c)
        out[c] = h00 * value(k)[c] + h10 * dt * out_tangent[c] + h01 * value(k + 1)[c] + h11 * dt * in_tangent[c];
      if (rotation) normalise(out.first(w));
      return;
    }
  }
}

std::optional<std::size_t> find_animation(std::span<const Animation> animations, std::string_view name) {
  if (name.empty()) return std::nullopt;  // unnamed animations are found by index alone
  for (std::size_t i = 0; i < animations.size(); ++i)
    if (animations[i].name == name) return i;
  std::size_t index = 0;
  const auto [end, error] = std::from_chars(name.data(), name.data() + name.size(), index);
  if (error != std::errc{} || end != name.data() + name.size() || index >= animations.size()) return std::nullopt;
  return index;
}

std::size_t animation_named(std::span<const Animation> animations, std::string_view name, const std::string& source) {
  if (animations.empty()) throw InputError(source, "has no animation to play");
  if (name.empty()) return 0;
  if (const std::optional<std::size_t> found = find_animation(animations, name)) return *found;
  std::string names;
  for (std::size_t i = 0; i < animations.size(); ++i)
    names += (i ? ", " : "") + (animations[i].name.empty() ? std::to_string(i) : "'" + animations[i].name + "'");
  throw InputError(source, "has no animation '" + std::string(name) + "' (it has " + names + ")");
}

}  // namespace facet
