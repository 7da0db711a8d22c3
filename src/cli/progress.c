/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The progress line of 'solve' and 'render' on a terminal: what the long
 * steps before the first iteration are doing (assembly, ordering,
 * factorisation, condensation: reported through linalg's cx_progress hook)
 * and the time since the run began, redrawn 5 times a second by a thread
 * of its own, since a factorisation is one long library call. Nothing when
 * stderr is not a terminal (a pipe, a file, a test's capture). */
#include "cli/progress.h"
#include "linalg/linalg.h"

#include <pthread.h>
#include <signal.h>
#include <stdio.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

static struct {
    pthread_mutex_t lock;
    pthread_cond_t wake;
    pthread_t thread;
    int running, stop, drawn;
    char what[32];
    double size;
    double t0;
    const cx_progress *prev;
    cx_progress hook;
} prog = {.lock = PTHREAD_MUTEX_INITIALIZER, .wake = PTHREAD_COND_INITIALIZER};

/* "1.2M", "132k", "850" */
static void progress_size(double n, char *buf, size_t len)
{
    if (n >= 1e6)
        snprintf(buf, len, "%.1fM", n / 1e6);
    else if (n >= 1e4)
        snprintf(buf, len, "%.0fk", n / 1e3);
    else
        snprintf(buf, len, "%.0f", n);
}

/* Called with the lock held. */
static void progress_draw(void)
{
    if (!prog.what[0])
        return;
    char size[16];
    progress_size(prog.size, size, sizeof size);
    fprintf(stderr, "\r\033[K%s %s dofs... %.1f s", prog.what, size, cx_clock_now() - prog.t0);
    fflush(stderr);
    prog.drawn = 1;
}

static void *progress_thread(void *arg)
{
    (void)arg;
    pthread_mutex_lock(&prog.lock);
    while (!prog.stop) {
        progress_draw();
        struct timespec ts;
        clock_gettime(CLOCK_REALTIME, &ts);
        ts.tv_nsec += 200000000L;
        if (ts.tv_nsec >= 1000000000L) {
            ts.tv_sec++;
            ts.tv_nsec -= 1000000000L;
        }
        pthread_cond_timedwait(&prog.wake, &prog.lock, &ts);
    }
    if (prog.drawn)
        fputs("\r\033[K", stderr);   /* the line goes: what follows starts at column 0 */
    fflush(stderr);
    pthread_mutex_unlock(&prog.lock);
    return NULL;
}

/* The hook, in the working thread: a new step is drawn at once. */
static void progress_step(void *ctx, const char *what, double size)
{
    (void)ctx;
    pthread_mutex_lock(&prog.lock);
    snprintf(prog.what, sizeof prog.what, "%s", what);
    prog.size = size;
    pthread_cond_signal(&prog.wake);
    pthread_mutex_unlock(&prog.lock);
}

void cli_progress_start(void)
{
    if (prog.running || !isatty(STDERR_FILENO))
        return;
    prog.stop = prog.drawn = 0;
    prog.what[0] = '\0';
    prog.t0 = cx_clock_now();
    /* Ctrl-C goes to the main thread, whose handler cancels the run */
    sigset_t all, old;
    sigfillset(&all);
    pthread_sigmask(SIG_SETMASK, &all, &old);
    int ok = pthread_create(&prog.thread, NULL, progress_thread, NULL) == 0;
    pthread_sigmask(SIG_SETMASK, &old, NULL);
    if (!ok)
        return;   /* no line: the run goes on */
    prog.running = 1;
    prog.hook = (cx_progress){progress_step, NULL};
    prog.prev = cx_progress_set(&prog.hook);
}

void cli_progress_stop(void)
{
    if (!prog.running)
        return;
    cx_progress_set(prog.prev);
    pthread_mutex_lock(&prog.lock);
    prog.stop = 1;
    pthread_cond_signal(&prog.wake);
    pthread_mutex_unlock(&prog.lock);
    pthread_join(prog.thread, NULL);
    prog.running = 0;
}
