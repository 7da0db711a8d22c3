/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Wall-clock time for timing steps and phases. */
#ifndef CX_CLOCK_H
#define CX_CLOCK_H

/* Seconds from an arbitrary fixed origin (monotonic clock). */
double cx_clock_now(void);

#endif
