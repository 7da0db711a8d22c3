/* SPDX-License-Identifier: GPL-3.0-or-later */
/* cli/progress.h: the progress line on stderr during the long steps of a
 * run (cli/progress.c). One at a time, started and stopped by the thread
 * that runs the steps. */
#ifndef CLI_PROGRESS_H
#define CLI_PROGRESS_H

/* Starts the line when stderr is a terminal (else does nothing) and
 * installs the hook (linalg.h cx_progress) in the calling thread. */
void cli_progress_start(void);
/* Erases the line and removes the hook; nothing if not started. Call it
 * before anything else is printed. */
void cli_progress_stop(void);

#endif
