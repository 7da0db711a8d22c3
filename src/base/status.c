/* SPDX-License-Identifier: GPL-3.0-or-later */
#include "base/status.h"

const char *cx_status_str(int status)
{
    switch (status) {
#define CX_STATUS_CASE_(name, value, msg) case value: return msg;
    CX_STATUS_LIST(CX_STATUS_CASE_)
#undef CX_STATUS_CASE_
    }
    return "unknown status";
}
