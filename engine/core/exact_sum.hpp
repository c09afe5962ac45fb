#pragma once
// ExactSum: the exact sum of doubles, whatever their order.
//
// Floating-point addition is not associative, so a sum split among threads (or, later, among
// MPI ranks) comes out with bits that depend on the split. This accumulator does not round:
// every finite double is an integer multiple of 2^-1074 below 2^1024, so the sum is kept as one
// fixed-point integer of about 2,100 bits, in 32-bit digits each held in an int64 word (room
// for 2^31 additions before a carry has to be passed on). Adding is integer addition, which is
// associative, so the sum of a set of values has the same bits in any order and any grouping;
// two accumulators merge exactly (word by word), and their words can be summed by MPI as
// integers. value() rounds the exact sum to the nearest double once, at the end.
// NaN and infinities are counted, not added: value() is NaN if a NaN was added or both
// infinities were, else the infinity added, as the plain sum would give.
//
// Cost: a few nanoseconds an addition (the digits touched are in L1), so it is meant for the
// sums a step reports or decides on (thermo, the solver's error), not for the pair loops.
#include <array>
#include <bit>
#include <cstdint>

namespace pbf {

class ExactSum {
 public:
  // Bit k of the fixed-point integer weighs 2^(k - 1074); a double's 53-bit significand at its
  // lowest position 2045 reaches bit 2098, and the sum of 2^64 such values 64 bits above that.
  static constexpr int kDigitBits = 32;
  static constexpr int kWords = (2098 + 64) / kDigitBits + 2;

  void add(double x) {
    const std::uint64_t bits = std::bit_cast<std::uint64_t>(x);
    const int biased = static_cast<int>((bits >> 52) & 0x7ff);
    if (biased == 0x7ff) return count_special(bits);
    // x = significand * 2^(lowest - 1074); subnormals have no hidden bit and the lowest position.
    std::uint64_t significand = bits & ((std::uint64_t(1) << 52) - 1);
    int lowest = 0;
    if (biased != 0) {
      significand |= std::uint64_t(1) << 52;
      lowest = biased - 1;
    }
    if (significand == 0) return;
    if (adds_since_normalised_ >= kNormaliseEvery) normalise();
    ++adds_since_normalised_;
    // The significand shifted into place spans at most three digits (its top one below 2^21).
    const int w = lowest / kDigitBits, shift = lowest % kDigitBits;
    const std::uint64_t low = significand << shift;
    const std::uint64_t high = shift ? significand >> (64 - shift) : 0;
    const std::int64_t sign = (bits >> 63) ? -1 : 1;
    word_[w] += sign * static_cast<std::int64_t>(low & 0xffffffffu);
    word_[w + 1] += sign * static_cast<std::int64_t>(low >> kDigitBits);
    word_[w + 2] += sign * static_cast<std::int64_t>(high);
  }
  void merge(const ExactSum& other);  // this += other, exactly
  double value() const;              // the exact sum, rounded to the nearest double

  // The words, normalised (each digit below 2^32, the sign in the top word), for an exact
  // reduction elsewhere: summing the words of several accumulators and assigning the result
  // back with set_words gives their exact total.
  std::array<std::int64_t, kWords> words() const;
  void set_words(const std::array<std::int64_t, kWords>& words);
  // The counts of NaNs, +infinities and -infinities added, reduced the same way.
  std::array<std::uint32_t, 3> specials() const { return {nans_, positive_infinities_, negative_infinities_}; }
  void set_specials(const std::array<std::uint32_t, 3>& counts) {
    nans_ = counts[0];
    positive_infinities_ = counts[1];
    negative_infinities_ = counts[2];
  }

 private:
  // A word holds digits below 2^32: 2^30 additions of a digit each stay far inside an int64.
  static constexpr std::uint32_t kNormaliseEvery = 1u << 30;
  void normalise();  // passes every digit's carry to the next word
  void count_special(std::uint64_t bits);  // an infinity or a NaN

  std::array<std::int64_t, kWords> word_{};
  std::uint32_t adds_since_normalised_ = 0;
  std::uint32_t nans_ = 0, positive_infinities_ = 0, negative_infinities_ = 0;
};

}  // namespace pbf
