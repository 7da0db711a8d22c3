/* SPDX-License-Identifier: GPL-3.0-or-later */
#include "base/escape.h"

#include <stdio.h>
#include <string.h>

size_t cx_escape_printable(const unsigned char *s, size_t n)
{
    unsigned c = s[0];
    if (c >= 0x20 && c < 0x7f)
        return 1;
    if (c < 0xc2 || c > 0xf4)   /* controls, DEL, continuation bytes, overlong leads */
        return 0;
    size_t len = c < 0xe0 ? 2 : c < 0xf0 ? 3 : 4;
    if (len > n)
        return 0;
    unsigned long cp = c & (0x7fu >> len);
    for (size_t k = 1; k < len; k++) {
        if ((s[k] & 0xc0) != 0x80)
            return 0;
        cp = (cp << 6) | (s[k] & 0x3fu);
    }
    /* overlong forms, surrogates, beyond U+10FFFF, and the C1 controls
     * (U+009B is a CSI on terminals that take 8-bit controls) */
    static const unsigned long least[5] = {0, 0, 0x80, 0x800, 0x10000};
    if (cp < least[len] || (cp >= 0xd800 && cp <= 0xdfff) || cp > 0x10ffff || cp < 0xa0)
        return 0;
    return len;
}

char *cx_escape(char *dst, size_t len, const char *src, size_t n)
{
    const unsigned char *s = (const unsigned char *)src;
    size_t o = 0;
    for (size_t i = 0; i < n;) {
        size_t k = cx_escape_printable(s + i, n - i);
        char esc[5];
        const char *piece = (const char *)s + i;
        size_t plen = k;
        if (k == 0) {
            if (s[i] == '\t' || s[i] == '\n' || s[i] == '\r')
                snprintf(esc, sizeof esc, "\\%c", s[i] == '\t' ? 't' : s[i] == '\n' ? 'n' : 'r');
            else
                snprintf(esc, sizeof esc, "\\x%02x", s[i]);
            piece = esc;
            plen = strlen(esc);
            k = 1;
        }
        if (o + plen >= len)
            break;
        memcpy(dst + o, piece, plen);
        o += plen;
        i += k;
    }
    dst[o] = '\0';
    return dst;
}
