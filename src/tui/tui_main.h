/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The explorer as a program: the one entry point src/main.c calls. Kept
 * apart from tui.h (the explorer's state and actions) so that the program
 * needs nothing of the explorer but this. */
#ifndef TUI_MAIN_H
#define TUI_MAIN_H

/* signorini [tui [SCENE] [options]]: run the explorer; argv[0] is the
 * command name. Returns the process exit status. */
int tui_main(int argc, char **argv);

#endif
