/* SPDX-License-Identifier: GPL-3.0-or-later */
/* signorini help-man [COMMAND] (hidden): the man page of the program or of
 * one command, in roff, written at build time (man/meson.build). The page
 * is the command's own --help, run in this process with stdout captured,
 * so that it comes from the same option tables (cx_opt_help) as the help
 * and the parser and cannot drift from them: the usage line becomes the
 * SYNOPSIS, option rows ("  -x, --name ARG   help") become .TP entries,
 * prose is filled and indented lists are kept as laid out. 'bench' gets a section per benchmark kind
 * and paper, read from the kinds and papers its help lists. */
#include "cli/cli.h"
#include "cx_config.h"

#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

enum { MAN_HELP_COL = 23, MAN_MAXKINDS = 32 };

/* The output of run(n, args) on stdout, NUL-terminated (free), or NULL. */
char *cli_capture(int (*run)(int, char **), int n, char **args)
{
    fflush(stdout);
    FILE *t = tmpfile();
    int saved = dup(STDOUT_FILENO);
    if (!t || saved < 0 || dup2(fileno(t), STDOUT_FILENO) < 0) {
        if (t)
            fclose(t);
        if (saved >= 0)
            close(saved);
        return NULL;
    }
    run(n, args);
    fflush(stdout);
    dup2(saved, STDOUT_FILENO);
    close(saved);
    off_t len = lseek(fileno(t), 0, SEEK_END);
    char *text = len >= 0 ? malloc((size_t)len + 1) : NULL;
    if (text && (lseek(fileno(t), 0, SEEK_SET) != 0 || read(fileno(t), text, (size_t)len) != (ssize_t)len)) {
        free(text);
        text = NULL;
    }
    if (text)
        text[len] = '\0';
    fclose(t);
    return text;
}

/* Text for roff: backslashes doubled as \e, '-' as \- (so that options can
 * be searched and copied), a leading '.' or '\'' made literal. */
static void man_text(const char *s, size_t n, FILE *out)
{
    if (n > 0 && (s[0] == '.' || s[0] == '\''))
        fputs("\\&", out);
    for (size_t k = 0; k < n; k++) {
        if (s[k] == '\\')
            fputs("\\e", out);
        else if (s[k] == '-')
            fputs("\\-", out);
        else
            fputc(s[k], out);
    }
}

static size_t man_indent(const char *s, size_t n)
{
    size_t k = 0;
    while (k < n && s[k] == ' ')
        k++;
    return k;
}

/* One --help text as roff: SYNOPSIS from its "usage:" lines when synopsis
 * is set, option rows as .TP, prose as written (no fill). */
static void man_body(const char *help, int synopsis, FILE *out)
{
    const char *p = help;
    int in_nf = 0, in_usage = 0;
    while (*p) {
        const char *nl = strchr(p, '\n');
        size_t n = nl ? (size_t)(nl - p) : strlen(p);
        size_t ind = man_indent(p, n);
        if (strncmp(p, "usage: ", 7) == 0) {
            if (in_nf)
                fputs(".fi\n", out);
            in_nf = 0;
            fputs(synopsis ? ".SH SYNOPSIS\n" : ".PP\n", out);
            man_text(p + 7, n - 7, out);
            fputc('\n', out);
            in_usage = 1;
        } else if (n == 0) {
            if (in_nf)
                fputs(".fi\n", out);
            if (in_usage && synopsis)
                fputs(".SH DESCRIPTION\n", out);
            else
                fputs(".PP\n", out);
            in_nf = in_usage = 0;
        } else if (in_usage) {
            fputs(".br\n", out);
            man_text(p + ind, n - ind, out);
            fputc('\n', out);
        } else if (ind == 2 && p[2] == '-') {
            /* an option row: "  -x, --name ARG" then its help at the column */
            if (in_nf)
                fputs(".fi\n", out);
            in_nf = 0;
            size_t end = n;
            const char *gap = strstr(p + 2, "  ");
            if (gap && (size_t)(gap - p) < n)
                end = (size_t)(gap - p);
            fputs(".TP\n\\fB", out);
            man_text(p + 2, end - 2, out);
            fputs("\\fR\n", out);
            size_t h = man_indent(p + end, n - end) + end;
            if (h < n) {
                man_text(p + h, n - h, out);
                fputc('\n', out);
            }
        } else if (ind >= MAN_HELP_COL - 1 && !in_nf) {
            /* a continuation of an option's help */
            man_text(p + ind, n - ind, out);
            fputc('\n', out);
        } else if (ind == 0) {
            /* prose: filled by roff */
            if (in_nf)
                fputs(".fi\n", out);
            in_nf = 0;
            man_text(p, n, out);
            fputc('\n', out);
        } else {
            /* an indented list (kinds, papers, cases): kept as laid out */
            if (!in_nf)
                fputs(".nf\n", out);
            in_nf = 1;
            man_text(p, n, out);
            fputc('\n', out);
        }
        p += n + (nl ? 1 : 0);
    }
    if (in_nf)
        fputs(".fi\n", out);
}

/* The words at the start of the lines of the block after the line
 * "heading" (up to a blank line): "  wp SCENE ..." gives "wp". */
static int man_block_words(const char *help, const char *heading, char words[][16], int max)
{
    const char *p = strstr(help, heading);
    int n = 0;
    if (!p)
        return 0;
    p = strchr(p, '\n');
    while (p && p[1] && p[1] != '\n' && n < max) {
        p++;
        if (p[0] == ' ' && p[1] == ' ' && isalnum((unsigned char)p[2])) {
            size_t len = strcspn(p + 2, " \n");
            if (len < 16) {
                memcpy(words[n], p + 2, len);
                words[n++][len] = '\0';
            }
        }
        p = strchr(p, '\n');
    }
    return n;
}

static void man_upper(const char *s, FILE *out)
{
    for (; *s; s++)
        fputc(toupper((unsigned char)*s), out);
}

/* The one-line summary of cmd from the program's "commands:" list. */
static void man_summary(const char *top, const char *cmd, char *buf, size_t len)
{
    snprintf(buf, len, "the %s command of signorini", cmd);
    const char *p = strstr(top, "commands:");
    size_t cl = strlen(cmd);
    while (p && (p = strchr(p, '\n')) != NULL && p[1] && p[1] != '\n') {
        p++;
        if (strncmp(p, "  ", 2) == 0 && strncmp(p + 2, cmd, cl) == 0 && (p[2 + cl] == ' ')) {
            const char *nl = strchr(p, '\n');
            size_t n = nl ? (size_t)(nl - p) : strlen(p);
            const char *gap = strstr(p + 2, "  ");
            if (gap && (size_t)(gap - p) < n) {
                size_t h = (size_t)(gap - p) + man_indent(gap, n - (size_t)(gap - p));
                snprintf(buf, len, "%.*s", (int)(n - h), p + h);
            }
            return;
        }
    }
}

int cli_man(int argc, char **argv, int (*run)(int, char **))
{
    static const char *const cmds[] = {"list", "solve", "render", "export", "bench", "tui", "version", NULL};
    const char *cmd = argc > 1 ? argv[1] : NULL;
    char prog[] = "signorini", help[] = "--help", paper[] = "paper";
    char *top_args[] = {prog, help, NULL};
    char *top = cli_capture(run, 2, top_args);
    if (!top)
        return cli_fail("help-man", "cannot capture the help");
    int known = !cmd;
    for (int k = 0; cmds[k] && !known; k++)
        known = strcmp(cmds[k], cmd) == 0;
    if (!known) {
        free(top);
        return cli_usage("help-man", "unknown command");
    }
    FILE *out = stdout;
    char summary[160];
    fputs(".\\\" generated by 'signorini help-man' from the option tables: do not edit\n", out);
    if (!cmd) {
        fprintf(out, ".TH SIGNORINI 1 \"\" \"signorini %s\" \"User Commands\"\n.SH NAME\n", CX_VERSION);
        fputs("signorini \\- elastic contact problems with and without friction\n", out);
        man_body(top, 1, out);
        fputs(".SH ENVIRONMENT\n.TP\n\\fBSIGNORINI_DATA\\fR\n"
              "the data directory (its scenes/ and shaders/), instead of share/signorini beside the program\n"
              ".TP\n\\fBSIGNORINI_SCENES\\fR\nscene directories, separated by ':', searched first\n"
              ".TP\n\\fBSIGNORINI_SHADERS\\fR\nthe shader directory, searched first\n.SH SEE ALSO\n", out);
        for (int k = 0; cmds[k]; k++)
            fprintf(out, "\\fBsignorini\\-%s\\fR(1)%s\n", cmds[k], cmds[k + 1] ? "," : "");
        free(top);
        return CX_EXIT_OK;
    }
    man_summary(top, cmd, summary, sizeof summary);
    free(top);
    fputs(".TH SIGNORINI-", out);
    man_upper(cmd, out);
    fprintf(out, " 1 \"\" \"signorini %s\" \"User Commands\"\n.SH NAME\nsignorini\\-%s \\- ", CX_VERSION, cmd);
    man_text(summary, strlen(summary), out);
    fputc('\n', out);
    char cmdbuf[32];
    snprintf(cmdbuf, sizeof cmdbuf, "%s", cmd);
    char *args[] = {prog, cmdbuf, help, NULL};
    char *text = cli_capture(run, 3, args);
    if (!text)
        return cli_fail("help-man", "cannot capture the help");
    man_body(text, 1, out);
    if (strcmp(cmd, "bench") == 0) {
        char kinds[MAN_MAXKINDS][16], papers[MAN_MAXKINDS][16];
        int nk = man_block_words(text, "\nkinds:", kinds, MAN_MAXKINDS);
        int np = man_block_words(text, "\npapers:", papers, MAN_MAXKINDS);
        for (int k = 0; k < nk; k++) {
            char *kargs[] = {prog, cmdbuf, kinds[k], help, NULL};
            char *kt = cli_capture(run, 4, kargs);
            fputs(".SH \"BENCH ", out);
            man_upper(kinds[k], out);
            fputs("\"\n", out);
            if (kt)
                man_body(kt, 0, out);
            free(kt);
            if (strcmp(kinds[k], "paper") != 0)
                continue;
            for (int q = 0; q < np; q++) {
                char *pargs[] = {prog, cmdbuf, paper, papers[q], help, NULL};
                char *pt = cli_capture(run, 5, pargs);
                fprintf(out, ".SS \"paper %s\"\n", papers[q]);
                if (pt)
                    man_body(pt, 0, out);
                free(pt);
            }
        }
    }
    free(text);
    fputs(".SH SEE ALSO\n\\fBsignorini\\fR(1)\n", out);
    return CX_EXIT_OK;
}
