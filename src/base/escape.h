/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Quoting input safely: a scene file, an option value or a path may hold
 * bytes a terminal acts on (ESC sequences, BEL, C1 controls) or bytes that
 * are not text. Every message that quotes input passes through cx_escape
 * (cx_diag_set does it for every diagnostic), so what reaches a terminal
 * is printable. */
#ifndef CX_ESCAPE_H
#define CX_ESCAPE_H

#include <stddef.h>

/* Copy the n bytes of src into dst (len bytes, len > 0, always
 * terminated; truncated on a whole escape) with C0 controls, DEL, C1
 * controls (U+0080..U+009F) and bytes that are not valid UTF-8 written as
 * \xNN ("\t", "\n", "\r" for those three); printable ASCII and valid UTF-8
 * from U+00A0 up pass unchanged. The output contains no byte that needs
 * escaping, so escaping twice changes nothing. Returns dst. */
char *cx_escape(char *dst, size_t len, const char *src, size_t n);

/* The length of the valid UTF-8 sequence of a printable character at s
 * (at most n bytes), or 0 if the byte at s must be escaped. */
size_t cx_escape_printable(const unsigned char *s, size_t n);

#endif
