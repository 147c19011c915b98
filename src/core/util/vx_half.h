/* vx_half.h: IEEE 754 binary16 ("half") conversion, round to nearest even,
 * with subnormals, infinities and NaN kept; no hardware support needed. */
#ifndef VX_HALF_H
#define VX_HALF_H

#include <stdint.h>
#include <string.h>

/* vx_half_from_float: the binary16 nearest to f (ties to even); values
 * beyond the largest half (65504) round to infinity as IEEE says. */
static inline uint16_t
vx_half_from_float(float f)
{
	uint32_t x, sign, mant;
	int32_t exp;

	memcpy(&x, &f, 4);
	sign = (x >> 16) & 0x8000u;
	exp = (int32_t)((x >> 23) & 0xff);
	mant = x & 0x7fffffu;
	if (exp == 0xff)                      /* Inf, NaN (quiet, payload kept) */
		return (uint16_t)(sign | 0x7c00u | (mant ? 0x200u | (mant >> 13) : 0));
	exp -= 127 - 15;
	if (exp >= 0x1f)                      /* overflow */
		return (uint16_t)(sign | 0x7c00u);
	if (exp <= 0) {                       /* subnormal half or zero */
		uint32_t m, shift, r, half, rest;

		if (exp < -10)
			return (uint16_t)sign;
		m = mant | 0x800000u;
		shift = (uint32_t)(14 - exp);
		r = m >> shift;
		rest = m & ((1u << shift) - 1);
		half = 1u << (shift - 1);
		if (rest > half || (rest == half && (r & 1)))
			r++;
		return (uint16_t)(sign | r);
	}
	{
		uint32_t r = ((uint32_t)exp << 10) | (mant >> 13);
		uint32_t rest = mant & 0x1fffu;

		if (rest > 0x1000u || (rest == 0x1000u && (r & 1)))
			r++;                  /* may carry into the exponent: right */
		return (uint16_t)(sign | r);
	}
}

/* vx_half_to_float: exact. */
static inline float
vx_half_to_float(uint16_t h)
{
	uint32_t sign = (uint32_t)(h & 0x8000u) << 16;
	uint32_t exp = (h >> 10) & 0x1f, mant = h & 0x3ffu, x;
	float f;

	if (exp == 0) {
		if (mant == 0) {
			x = sign;
		} else {                      /* subnormal: normalize */
			exp = 127 - 15 + 1;
			while (!(mant & 0x400u)) {
				mant <<= 1;
				exp--;
			}
			x = sign | (exp << 23) | ((mant & 0x3ffu) << 13);
		}
	} else if (exp == 0x1f) {
		x = sign | 0x7f800000u | (mant << 13);
	} else {
		x = sign | ((exp + 127 - 15) << 23) | (mant << 13);
	}
	memcpy(&f, &x, 4);
	return f;
}

#endif
