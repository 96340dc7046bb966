#pragma once
// An exact accumulator for sums of doubles (docs/parallel.md, "Determinism"): the sum it
// holds is the exact real sum of its terms, so the rounded total does not depend on the
// order of the terms, on the thread count or on how the terms are split among MPI ranks.
// The energy audit, the momentum and the per-step boundary and source work use it.
//
// Representation: a signed fixed-point integer in 32-bit digits, digit i weighing
// 2^(32 i - 1074) (the least subnormal is 2^-1074), each digit an int64 with 31 bits of
// headroom for carries. A term adds its 53-bit significand, shifted, to three digits;
// carries are propagated every 2^30 terms, and when the digits are merged or read.
#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

namespace stagger {

class ExactSum {
 public:
  // 2098 bits of doubles plus room for the carries of 2^31 * 2^1024: 68 digits of 32 bits.
  static constexpr int kDigits = 68;
  // The digits, then the counts of NaN, +Inf and -Inf terms (a sum over ranks adds them all).
  static constexpr int kWords = kDigits + 3;

  void add(double value) {
    const std::uint64_t bits = std::bit_cast<std::uint64_t>(value);
    const int exponent = static_cast<int>((bits >> 52) & 0x7ff);
    std::uint64_t significand = bits & ((std::uint64_t{1} << 52) - 1);
    if (exponent == 0x7ff) {  // Inf or NaN: counted apart, the total is not finite
      ++words_[std::isnan(value) ? kDigits : value > 0 ? kDigits + 1 : kDigits + 2];
      return;
    }
    if (exponent != 0) significand |= std::uint64_t{1} << 52;
    if (significand == 0) return;
    // value = significand * 2^(max(exponent, 1) - 1075) = significand * 2^(position - 1074).
    const int position = (exponent == 0 ? 1 : exponent) - 1;
    const int digit = position >> 5, shift = position & 31;
    // The 85-bit significand << shift in three digits (the 64-bit shift keeps bits 0..63).
    const std::uint64_t low = significand << shift;
    const auto d0 = static_cast<std::int64_t>(low & 0xffffffffu);
    const auto d1 = static_cast<std::int64_t>(low >> 32);
    const auto d2 = static_cast<std::int64_t>(shift == 0 ? 0 : significand >> (64 - shift));
    if (bits >> 63) {
      words_[digit] -= d0, words_[digit + 1] -= d1, words_[digit + 2] -= d2;
    } else {
      words_[digit] += d0, words_[digit + 1] += d1, words_[digit + 2] += d2;
    }
    if (++pending_ >= (1 << 30)) normalize();
  }

  // Adds another accumulator's terms (exactly).
  void merge(const ExactSum& other) {
    ExactSum o = other;
    o.normalize();
    normalize();
    for (int i = 0; i < kWords; ++i) words_[i] += o.words_[i];
    normalize();
  }

  // The total, rounded (to within an ulp; a fixed function of the exact sum).
  double value() const {
    ExactSum s = *this;
    s.normalize();
    const std::int64_t nans = s.words_[kDigits], positive_inf = s.words_[kDigits + 1];
    const std::int64_t negative_inf = s.words_[kDigits + 2];
    if (nans > 0 || (positive_inf > 0 && negative_inf > 0)) return std::numeric_limits<double>::quiet_NaN();
    if (positive_inf > 0) return std::numeric_limits<double>::infinity();
    if (negative_inf > 0) return -std::numeric_limits<double>::infinity();
    // After normalize every digit but the top one is in [0, 2^32); the top one carries the sign.
    const bool negative = s.words_[kDigits - 1] < 0;
    if (negative) s.negate();
    int top = kDigits - 1;
    while (top >= 0 && s.words_[top] == 0) --top;
    if (top < 0) return 0.0;
    // The top three digits (at least 65 significant bits), summed from the smallest: the
    // rounding error of the sum is below an ulp of the total, and it depends only on the digits.
    double total = 0;
    for (int i = std::max(0, top - 2); i <= top; ++i)
      total += std::ldexp(static_cast<double>(s.words_[i]), 32 * i - 1074);
    return negative ? -total : total;
  }

  // The raw words, for a sum over MPI ranks (normalized first: every digit of a normalized
  // accumulator but the top is below 2^32, so ranks can add them as int64).
  std::array<std::int64_t, kWords>& words() {
    normalize();
    return words_;
  }

 private:
  void normalize() {
    for (int i = 0; i + 1 < kDigits; ++i) {
      const std::int64_t carry = words_[i] >> 32;  // floor division by 2^32
      words_[i] -= carry * (std::int64_t{1} << 32);
      words_[i + 1] += carry;
    }
    pending_ = 0;
  }
  // Two's complement of the whole number (top digit negative -> magnitude, normalized).
  void negate() {
    for (int i = 0; i < kDigits; ++i) words_[i] = -words_[i];
    normalize();
  }

  std::array<std::int64_t, kWords> words_{};
  std::int64_t pending_ = 0;
};

}  // namespace stagger
