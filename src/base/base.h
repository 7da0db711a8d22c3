/* SPDX-License-Identifier: GPL-3.0-or-later */
/* base/: what every layer needs — status codes, the one-line diagnostic,
 * the allocator, parameter tables, strict parsing, the clock and sorting
 * by keys. */
#ifndef CX_BASE_H
#define CX_BASE_H

#include "base/status.h"
#include "base/diag.h"
#include "base/escape.h"
#include "base/alloc.h"
#include "base/param.h"
#include "base/parse.h"
#include "base/clock.h"
#include "base/sort.h"

#define CX_PI 3.14159265358979323846

#endif
