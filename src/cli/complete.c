/* SPDX-License-Identifier: GPL-3.0-or-later */
/* signorini help-completion bash|zsh|scenes (hidden). The bash and zsh
 * completion scripts are written at build time (man/meson.build) from each
 * command's --help, captured as for the man pages (cli/man.c), so their
 * options come from the same cx_opt tables; method ids come from the
 * registry. Scene ids depend on where the data is at completion time, so
 * the scripts ask 'signorini help-completion scenes', which lists them
 * with the library's own search (cx_scene_list). Option values: a method
 * for ID arguments, the words of "a|b" arguments or of a help that starts
 * "a | b | c", file names for FILE. */
#include "cli/cli.h"

#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { COMP_MAXOPTS = 64, COMP_MAXCTX = 16, COMP_WORD = 48, COMP_HELP = 80 };

typedef struct {
    char name[COMP_WORD];      /* "--max-iter" */
    char shortn[4];            /* "-h" or "" */
    char values[COMP_HELP];    /* "@methods", "@files", "a b c" or "" (none), "-" (flag) */
    char help[COMP_HELP];      /* the help's first line */
} comp_opt;

typedef struct {
    char words[COMP_WORD];     /* "solve", "bench wp" */
    int scene;                 /* its usage names a SCENE argument */
    comp_opt opts[COMP_MAXOPTS];
    int nopts;
} comp_ctx;

static void comp_copy(char *dst, size_t len, const char *s, size_t n)
{
    if (n >= len)
        n = len - 1;
    memcpy(dst, s, n);
    dst[n] = '\0';
}

/* Does s[0..n) contain the text t? */
static int comp_has(const char *s, size_t n, const char *t)
{
    size_t tn = strlen(t);
    for (size_t k = 0; k + tn <= n; k++)
        if (memcmp(s + k, t, tn) == 0)
            return 1;
    return 0;
}

/* The option rows of one --help text into c. */
static void comp_parse(const char *help, comp_ctx *c)
{
    for (const char *p = help; p && *p;) {
        const char *nl = strchr(p, '\n');
        size_t n = nl ? (size_t)(nl - p) : strlen(p);
        if (n > 3 && p[0] == ' ' && p[1] == ' ' && p[2] == '-' && c->nopts < COMP_MAXOPTS) {
            comp_opt *o = &c->opts[c->nopts];
            memset(o, 0, sizeof *o);
            const char *q = p + 2, *end = p + n;
            const char *gap = strstr(q, "  ");
            const char *left_end = gap && gap < end ? gap : end;
            if (q[1] != '-') {   /* "-x, --name" */
                comp_copy(o->shortn, sizeof o->shortn, q, 2);
                q += 4;
            }
            size_t w = strcspn(q, " \n");
            if (q + w > left_end)
                w = (size_t)(left_end - q);
            comp_copy(o->name, sizeof o->name, q, w);
            const char *arg = q + w < left_end ? q + w + 1 : NULL;
            size_t argn = arg ? (size_t)(left_end - arg) : 0;
            const char *h = left_end;
            while (h < end && *h == ' ')
                h++;
            comp_copy(o->help, sizeof o->help, h, (size_t)(end - h));
            if (!arg) {
                snprintf(o->values, sizeof o->values, "-");
            } else if (comp_has(arg, argn, "ID") || comp_has(arg, argn, "a,b,") ||
                       strcmp(o->name, "--method") == 0 || strcmp(o->name, "--methods") == 0) {
                snprintf(o->values, sizeof o->values, "@methods");
            } else if (comp_has(arg, argn, "FILE")) {
                snprintf(o->values, sizeof o->values, "@files");
            } else if (memchr(arg, '|', argn)) {
                comp_copy(o->values, sizeof o->values, arg, argn);
            } else if (strstr(o->help, " | ") && strcspn(o->help, "(;,") > (size_t)(strstr(o->help, " | ") - o->help)) {
                size_t hn = strcspn(o->help, "(;,");
                comp_copy(o->values, sizeof o->values, o->help, hn);
            }
            /* "a|b" and "a | b | c" as "a b c" */
            char tmp[COMP_HELP];
            size_t k = 0;
            for (const char *v = o->values; *v && k + 1 < sizeof tmp; v++)
                if (*v == '|')
                    tmp[k++] = ' ';
                else if (*v != ' ' || (k > 0 && tmp[k - 1] != ' '))
                    tmp[k++] = *v;
            while (k > 0 && tmp[k - 1] == ' ')
                k--;
            tmp[k] = '\0';
            if (o->values[0] != '@' && o->values[0] != '-')
                snprintf(o->values, sizeof o->values, "%s", tmp);
            for (char *x = o->help; *x; x++)   /* quotes and brackets would end zsh's specs */
                if (*x == '\'' || *x == '[' || *x == ']' || *x == ':' || *x == '`' || *x == '$' || *x == '\\')
                    *x = ' ';
            c->nopts++;
        }
        p = nl ? nl + 1 : NULL;
    }
}

/* Words of the lines after heading in text ("  wp SCENE ..." -> "wp"). */
static int comp_block(const char *text, const char *heading, char words[][COMP_WORD], int max)
{
    const char *p = strstr(text, heading);
    int n = 0;
    p = p ? strchr(p, '\n') : NULL;
    while (p && p[1] && p[1] != '\n' && n < max) {
        p++;
        if (p[0] == ' ' && p[1] == ' ' && isalnum((unsigned char)p[2]))
            comp_copy(words[n++], COMP_WORD, p + 2, strcspn(p + 2, " \n"));
        p = strchr(p, '\n');
    }
    return n;
}

static int comp_add(comp_ctx *ctx, int n, int (*run)(int, char **), const char *words)
{
    char buf[COMP_WORD * 2], prog[] = "signorini", help[] = "--help";
    char *args[8] = {prog};
    int na = 1;
    snprintf(ctx[n].words, sizeof ctx[n].words, "%s", words);
    snprintf(buf, sizeof buf, "%s", words);
    for (char *t = strtok(buf, " "); t && na < 6; t = strtok(NULL, " "))
        args[na++] = t;
    args[na++] = help;
    args[na] = NULL;
    char *text = cli_capture(run, na, args);
    ctx[n].nopts = 0;
    ctx[n].scene = 0;
    if (text) {
        comp_parse(text, &ctx[n]);
        const char *u = strstr(text, "usage:");
        ctx[n].scene = u && comp_has(u, strcspn(u, "\n"), "SCENE");
    }
    free(text);
    return n + 1;
}

static void comp_values(const comp_opt *o, int zsh, FILE *out)
{
    if (strcmp(o->values, "@methods") == 0) {
        fputs(zsh ? "(auto" : "auto", out);
        for (int k = 0; k < cx_method_count(); k++)
            fprintf(out, " %s", cx_method_at(k)->id);
        fputs(zsh ? ")" : "", out);
    } else if (strcmp(o->values, "@files") == 0) {
        fputs(zsh ? "_files" : "", out);
    } else if (zsh) {
        fprintf(out, o->values[0] ? "(%s)" : " ", o->values);
    } else {
        fputs(o->values, out);
    }
}

static void comp_bash(const comp_ctx *ctx, int nctx, char cmds[][COMP_WORD], int ncmds, const char *kinds,
                      FILE *out)
{
    fputs("# bash completion for signorini, generated by 'signorini help-completion bash'\n"
          "# from the commands' option tables: do not edit\n"
          "_signorini()\n{\n"
          "    local cur=${COMP_WORDS[COMP_CWORD]} prev=${COMP_WORDS[COMP_CWORD-1]}\n"
          "    local ctx=${COMP_WORDS[1]} opts= scene=0\n"
          "    if [ \"$COMP_CWORD\" -eq 1 ]; then\n"
          "        COMPREPLY=($(compgen -W \"", out);
    for (int k = 0; k < ncmds; k++)
        fprintf(out, "%s ", cmds[k]);
    fputs("--help --version\" -- \"$cur\"))\n        return\n    fi\n"
          "    if [ \"$ctx\" = bench ] && [ \"$COMP_CWORD\" -gt 2 ]; then\n"
          "        ctx=\"bench ${COMP_WORDS[2]}\"\n"
          "        [ \"${COMP_WORDS[2]}\" = paper ] && [ \"$COMP_CWORD\" -gt 3 ] && ctx=\"bench paper ${COMP_WORDS[3]}\"\n"
          "    fi\n    case $ctx in\n", out);
    for (int c = 0; c < nctx; c++) {
        fprintf(out, "    '%s')\n        opts='", ctx[c].words);
        for (int k = 0; k < ctx[c].nopts; k++)
            fprintf(out, "%s%s%s%s", k ? " " : "", ctx[c].opts[k].name, ctx[c].opts[k].shortn[0] ? " " : "",
                    ctx[c].opts[k].shortn);
        fputs("'\n        case $prev in\n", out);
        for (int k = 0; k < ctx[c].nopts; k++) {
            const comp_opt *o = &ctx[c].opts[k];
            if (o->values[0] == '-')
                continue;
            if (strcmp(o->values, "@files") == 0) {
                fprintf(out, "        %s) COMPREPLY=($(compgen -f -- \"$cur\")); return ;;\n", o->name);
                continue;
            }
            fprintf(out, "        %s) COMPREPLY=($(compgen -W '", o->name);
            comp_values(o, 0, out);
            fputs("' -- \"$cur\")); return ;;\n", out);
        }
        fprintf(out, "        esac\n        scene=%d ;;\n", ctx[c].scene);
    }
    fputs("    esac\n"
          "    if [[ $cur == -* ]]; then\n"
          "        COMPREPLY=($(compgen -W \"$opts\" -- \"$cur\"))\n"
          "    elif [ \"$ctx\" = bench ]; then\n"
          "        COMPREPLY=($(compgen -W '", out);
    fputs(kinds, out);
    fputs("' -- \"$cur\"))\n"
          "    elif [ \"$ctx\" = 'bench paper' ]; then\n"
          "        COMPREPLY=($(compgen -W \"$(\"${COMP_WORDS[0]}\" help-completion papers 2>/dev/null)\" -- \"$cur\"))\n"
          "    elif [ \"$scene\" = 1 ]; then\n"
          "        COMPREPLY=($(compgen -W \"$(\"${COMP_WORDS[0]}\" help-completion scenes 2>/dev/null)\" -- \"$cur\"))\n"
          "    fi\n}\ncomplete -o default -F _signorini signorini\n", out);
}

static void comp_zsh(const comp_ctx *ctx, int nctx, char cmds[][COMP_WORD], int ncmds, const char *kinds,
                     FILE *out)
{
    fputs("#compdef signorini\n# zsh completion for signorini, generated by 'signorini help-completion zsh'\n"
          "# from the commands' option tables: do not edit\n"
          "_signorini_scenes() { local -a s; s=(${(f)\"$(${words[1]} help-completion scenes 2>/dev/null)\"}); "
          "_describe scene s; }\n"
          "_signorini() {\n  local ctx\n  if (( CURRENT == 2 )); then\n    local -a cmds; cmds=(", out);
    for (int k = 0; k < ncmds; k++)
        fprintf(out, "%s ", cmds[k]);
    fputs(")\n    _describe command cmds; return\n  fi\n  ctx=$words[2]\n"
          "  if [[ $ctx == bench ]]; then\n"
          "    if (( CURRENT == 3 )); then local -a k; k=(", out);
    fputs(kinds, out);
    fputs("); _describe kind k; return; fi\n"
          "    ctx=\"bench $words[3]\"\n"
          "    if [[ $words[3] == paper ]]; then\n"
          "      if (( CURRENT == 4 )); then local -a p; p=(${(f)\"$(${words[1]} help-completion papers 2>/dev/null)\"}); "
          "_describe paper p; return; fi\n"
          "      ctx=\"bench paper $words[4]\"\n    fi\n  fi\n  case $ctx in\n", out);
    for (int c = 0; c < nctx; c++) {
        fprintf(out, "  '%s')\n    _arguments -s", ctx[c].words);
        for (int k = 0; k < ctx[c].nopts; k++) {
            const comp_opt *o = &ctx[c].opts[k];
            fprintf(out, " \\\n      '%s[%s]", o->name, o->help);
            if (o->values[0] != '-') {
                fputs(":value:", out);
                comp_values(o, 1, out);
            }
            fputc('\'', out);
        }
        fputs(ctx[c].scene ? " \\\n      '*:scene:_signorini_scenes' ;;\n" : " ;;\n", out);
    }
    fputs("  esac\n}\n_signorini \"$@\"\n", out);
}

int cli_completion(int argc, char **argv, int (*run)(int, char **))
{
    const char *what = argc > 1 ? argv[1] : "";
    cx_diag d;
    if (strcmp(what, "scenes") == 0) {
        char (*ids)[CX_SCENE_NAMELEN] = NULL;
        int n = 0;
        if (cx_scene_list(&ids, &n, &d))
            return cli_fail("help-completion", d.msg);
        for (int k = 0; k < n; k++)
            printf("%s\n", ids[k]);
        cx_free(ids);
        return CX_EXIT_OK;
    }
    char prog[] = "signorini", help[] = "--help", bench[] = "bench";
    char *top_args[] = {prog, help, NULL}, *bench_args[] = {prog, bench, help, NULL};
    char *top = cli_capture(run, 2, top_args), *btext = cli_capture(run, 3, bench_args);
    static char cmds[COMP_MAXCTX][COMP_WORD], kinds[COMP_MAXCTX][COMP_WORD], papers[COMP_MAXCTX][COMP_WORD];
    int ncmds = top ? comp_block(top, "\ncommands:", cmds, COMP_MAXCTX) : 0;
    int nk = btext ? comp_block(btext, "\nkinds:", kinds, COMP_MAXCTX) : 0;
    int np = btext ? comp_block(btext, "\npapers:", papers, COMP_MAXCTX) : 0;
    free(top);
    free(btext);
    if (strcmp(what, "papers") == 0) {
        for (int k = 0; k < np; k++)
            printf("%s\n", papers[k]);
        return CX_EXIT_OK;
    }
    int bash = strcmp(what, "bash") == 0;
    if (!bash && strcmp(what, "zsh") != 0)
        return cli_usage("help-completion", "expected bash, zsh, scenes or papers");
    static comp_ctx ctx[3 * COMP_MAXCTX];
    int nctx = 0;
    for (int k = 0; k < ncmds; k++)
        if (strcmp(cmds[k], "bench") != 0)
            nctx = comp_add(ctx, nctx, run, cmds[k]);
    for (int k = 0; k < nk; k++) {
        char w[COMP_WORD];
        snprintf(w, sizeof w, "bench %.30s", kinds[k]);
        nctx = comp_add(ctx, nctx, run, w);
    }
    for (int k = 0; k < np; k++) {
        char w[COMP_WORD];
        snprintf(w, sizeof w, "bench paper %.20s", papers[k]);
        nctx = comp_add(ctx, nctx, run, w);
    }
    char kindlist[COMP_MAXCTX * COMP_WORD] = "";
    for (int k = 0; k < nk; k++) {
        strcat(kindlist, k ? " " : "");
        strcat(kindlist, kinds[k]);
    }
    if (bash)
        comp_bash(ctx, nctx, cmds, ncmds, kindlist, stdout);
    else
        comp_zsh(ctx, nctx, cmds, ncmds, kindlist, stdout);
    return CX_EXIT_OK;
}
