/* pnm_priv.h: what the Netpbm-style readers (pfm.c, pgm.c) share. */
#ifndef VX_PNM_PRIV_H
#define VX_PNM_PRIV_H

#include <stddef.h>

/* vx_pnm_decimal: the decimal integer of 1 to 9 digits at p[*pos] (n
 * bytes), *pos moved past it; -1 (nothing moved but the digits read)
 * when there is none or it has more digits. */
int vx_pnm_decimal(const unsigned char *p, size_t n, size_t *pos,
    long *out);

#endif
