#include "engine/core/exact_sum.hpp"

#include <cmath>
#include <limits>

namespace pbf {

namespace {

// Passes every digit's carry to the next word: digits in [0, 2^32), the sign in the top word.
void carry_through(std::array<std::int64_t, ExactSum::kWords>& w) {
  for (int i = 0; i + 1 < ExactSum::kWords; ++i) {
    const std::int64_t carry = w[i] >> ExactSum::kDigitBits;  // arithmetic shift: floor division
    w[i] -= carry * (std::int64_t(1) << ExactSum::kDigitBits);
    w[i + 1] += carry;
  }
}

}  // namespace

void ExactSum::count_special(std::uint64_t bits) {
  if (bits & ((std::uint64_t(1) << 52) - 1)) ++nans_;
  else if (bits >> 63) ++negative_infinities_;
  else ++positive_infinities_;
}

void ExactSum::merge(const ExactSum& other) {
  ExactSum b = other;
  b.normalise();
  normalise();
  for (int i = 0; i < kWords; ++i) word_[i] += b.word_[i];
  adds_since_normalised_ = 2;  // two normalised sums: every word below 2^33 in magnitude
  nans_ += other.nans_;
  positive_infinities_ += other.positive_infinities_;
  negative_infinities_ += other.negative_infinities_;
}

void ExactSum::normalise() {
  carry_through(word_);
  adds_since_normalised_ = 0;
}

std::array<std::int64_t, ExactSum::kWords> ExactSum::words() const {
  ExactSum copy = *this;
  copy.normalise();
  return copy.word_;
}

void ExactSum::set_words(const std::array<std::int64_t, kWords>& words) {
  word_ = words;
  adds_since_normalised_ = kNormaliseEvery;  // normalised before the next addition
}

double ExactSum::value() const {
  if (nans_ > 0 || (positive_infinities_ > 0 && negative_infinities_ > 0)) return std::numeric_limits<double>::quiet_NaN();
  if (positive_infinities_ > 0) return std::numeric_limits<double>::infinity();
  if (negative_infinities_ > 0) return -std::numeric_limits<double>::infinity();
  std::array<std::int64_t, kWords> w = words();
  // The sign is the top word's; work on the magnitude.
  const bool negative = w[kWords - 1] < 0;
  if (negative) {
    for (auto& d : w) d = -d;
    carry_through(w);
  }
  int top = kWords - 1;
  while (top >= 0 && w[top] == 0) --top;
  if (top < 0) return 0.0;
  // The top three digits (at least 65 significant bits) and a sticky bit for the rest: the
  // conversion of that integer to double then rounds as the exact value would.
  const int low = top >= 2 ? top - 2 : 0;
  unsigned __int128 head = 0;
  for (int i = top; i >= low; --i) head = (head << kDigitBits) | static_cast<std::uint64_t>(w[i]);
  bool sticky = false;
  for (int i = 0; i < low; ++i) sticky |= w[i] != 0;
  if (sticky) head |= 1;
  const double magnitude = std::ldexp(static_cast<double>(head), kDigitBits * low - 1074);
  return negative ? -magnitude : magnitude;
}

}  // namespace pbf
