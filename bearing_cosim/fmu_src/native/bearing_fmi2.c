/* Native FMI 2.0 co-simulation layer of the bearing FMU.
 *
 * The model runs in its own process, one per instance: fmi2Instantiate starts resources/launch.sh (which
 * picks the Python) with resources/model_process.py, the pythonfmu slave's server. No Python is linked or
 * loaded into the master.
 *
 *  - Transport: one anonymous shared-memory segment (memfd, inherited as fd 3: no name, nothing to leak).
 *    Each FMI call that needs the model is one exchange: a request (the inputs set since the last exchange,
 *    then the command) and a response (status, mode, log records, results). The waiting side spins briefly
 *    and then sleeps on the futex of the sequence word the other side bumps; no core burns while the master
 *    is busy elsewhere.
 *  - fmi2DoStep is exactly one exchange; its response carries every output. In step mode fmi2Set* of inputs
 *    and fmi2Get* are served from this layer's copy of the variables; every other call (parameters,
 *    initialisation, refused sets with their reasons) goes to the model.
 *  - Faults: if the model process exits, is killed or does not answer within BEARING_FMU_STEP_TIMEOUT
 *    (fmi2DoStep, default 600 s) or BEARING_FMU_INIT_TIMEOUT (any other call, default 900 s), the call
 *    returns fmi2Error, the reason (exit status or signal, the tail of the model's stderr) goes to the
 *    logger, the process is killed and reaped and every later call returns fmi2Error. The model process
 *    exits when the master dies (it watches its parent).
 *  - Instances share nothing: two instances stepped from two threads run in parallel.
 *  - Remote model (bearing_tcp.c): with BEARING_FMU_SERVER=host:port (always on Windows, default
 *    127.0.0.1:7410) the instance's model process runs on a model server (bearing serve) and every exchange is
 *    one request and one response frame over TCP, with the same bytes as in the shared memory.
 *
 * Local model process: Linux (memfd, futex, posix_spawn). Remote: Linux and Windows. C99 with GNU extensions.
 */
#define _GNU_SOURCE
#include "fmi2_min.h"
#include "bearing_tcp.h"

#include <errno.h>
#include <limits.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <math.h>
#include <time.h>
#ifdef _WIN32
#include <sys/types.h>
#else
#include <fcntl.h>
#include <linux/futex.h>
#include <signal.h>
#include <spawn.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <sched.h>
#include <unistd.h>
#include <dlfcn.h>

extern char **environ;
#endif

#define PROTOCOL 2u
#define SHM_MAGIC 0x58475242u   /* "BRGX" */
#define MODEL_MAGIC 0x42524732u /* marks a live component */
#define SHM_SIZE (64u << 20)    /* sparse: only touched pages use memory */
#define HDR 4096u
/* header offsets (model_process.py) */
#define O_MAGIC 0
#define O_VERSION 4
#define O_REQ 8
#define O_RESP 12
#define O_CMD 16
#define O_STATUS 20
#define O_MODE 24
#define O_FLAGS 28
#define O_REQLEN 32
#define O_RESPLEN 40
#define O_TIME 48
#define O_BUSY 56
#define O_PID 64
#define O_PROG 72  /* u32: byte offset of the model's live integration time (double), 0: none */
#define O_MCPU 76  /* i32: the processor the master sent the last request from (sched_getcpu), -1: unknown */
#define O_WCPU 80  /* i32: the processor the model process sent its last answer from, -1: unknown */
#define F_SNAPSHOT 1u

enum { C_HELLO = 1, C_DEBUG, C_SETUP, C_ENTER, C_EXIT, C_STEP, C_TERMINATE, C_RESET, C_FREE, C_GET, C_SET,
       C_GETSTATE, C_SETSTATE, C_FREESTATE, C_SERIALIZE, C_DESERIALIZE, C_UNSUPPORTED };
enum { T_REAL, T_INTEGER, T_BOOLEAN, T_STRING };
enum { M_INSTANTIATED, M_INIT, M_STEP, M_FAILED, M_TERMINATED };
enum { CAUS_PARAMETER, CAUS_CALCULATED, CAUS_INPUT, CAUS_OUTPUT, CAUS_LOCAL, CAUS_INDEPENDENT };

typedef struct {
    unsigned vr;
    int type, caus, out_idx, dirty;
    double r;
    int i;
    char *s;
    char *name; /* the variable's name (fmi2GetDirectionalDerivative finds its variables by name) */
} Var;

typedef struct {
    unsigned magic;
    fmi2CallbackLogger logger;
    fmi2ComponentEnvironment env;
    char *name;
    pid_t pid;
    int log_fd;
    unsigned char *shm;
    uint32_t seq;
    int dead;     /* the model process is gone: every call returns fmi2Error */
    int mode;
    double time, busy;
    double step_expect; /* the model process's time in the last fmi2DoStep [s] */
    double step_h;      /* the communication step of the fmi2DoStep being sent [s] */
    double spin_score;  /* running share of steps whose answer came during a predicted spin */
    double short_score; /* the same for the spin through a short step */
    double tail;        /* running mean of the time from the integration's end to the answer [s] */
    unsigned long n_wait[4]; /* step answers seen by: the first spin, a predicted spin, the futex (asleep),
                                a spin through the step */
    int last_wait;           /* which of them saw the last answer */
    int mcpu;                /* the processor the last request was sent from (-1: unknown) */
    unsigned long n_shared;  /* requests sent from the processor the model process last answered from */
    unsigned long ex_hist[4][5]; /* exchange time (request to answer seen, less the model's busy time) per kind,
                                    in bins < 10, < 20, < 40, < 80, >= 80 us (BEARING_FMU_WAIT_STATS) */
    int wait_mode;           /* WAIT_AUTO, WAIT_SLEEP, WAIT_SPIN (BEARING_FMU_WAIT) */
    int hold;                /* steps left without spinning through (the model process waited for a processor) */
    double delay_prev, t_prev; /* the model process's run delay [s] (/proc/<pid>/schedstat) and when read */
    double init_timeout, step_timeout;
    Var *vars;
    int nvars;
    int *by_vr; /* value reference -> index into vars, -1 */
    unsigned nvr;
    int *pending; /* indices of inputs set locally since the last exchange */
    int npending;
    int *out_var; /* output index of the step response -> index into vars */
    int nout;
    char **strs; /* fmi2GetString results of a forwarded call (valid until the next call) */
    size_t nstrs;
    unsigned char *ser; /* serialized state of ser_id (fmi2SerializedFMUstateSize, then fmi2SerializeFMUstate) */
    size_t ser_len;
    uint64_t ser_id;
    BTcp *tcp;          /* the connection to the model server (remote model), else NULL */
    int remote;         /* the instance's model runs on a model server (c->shm is a private buffer) */
} Comp;

/* ---------------------------------------------------------------------------------------------- */
/* logging                                                                                         */

/* The message is passed as the format string with every '%' doubled and no further arguments, so that
 * masters that format it (as FMI 2.0 specifies) and masters that print it as is both show the text. */
static void log_to(fmi2CallbackLogger logger, fmi2ComponentEnvironment env, const char *name, fmi2Status st,
                   const char *cat, const char *msg) {
    if (!logger) return;
    size_t n = strlen(msg), extra = 0;
    for (size_t i = 0; i < n; i++) extra += msg[i] == '%';
    char *fmt = (char *)malloc(n + extra + 1);
    if (!fmt) return;
    char *q = fmt;
    for (size_t i = 0; i < n; i++) {
        *q++ = msg[i];
        if (msg[i] == '%') *q++ = '%';
    }
    *q = '\0';
    logger(env, name ? name : "", st, cat, fmt);
    free(fmt);
}

#ifdef _WIN32
#define PRINTF_FORMAT gnu_printf /* mingw-w64's C99 printf (__USE_MINGW_ANSI_STDIO) */
#else
#define PRINTF_FORMAT printf
#endif
static void mlog(Comp *c, fmi2Status st, const char *fmt, ...) __attribute__((format(PRINTF_FORMAT, 3, 4)));
static void mlog(Comp *c, fmi2Status st, const char *fmt, ...) {
    char msg[8192];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    log_to(c->logger, c->env, c->name, st, st == fmi2Error || st == fmi2Fatal ? "logError" : "logInfo", msg);
}

/* Log records "<status>\x1f<category>\x1f<message>\0" repeated (copied out of the shared memory first). */
static void emit_logs(Comp *c, const unsigned char *src, size_t len) {
    if (!len || !c->logger) return;
    char *buf = (char *)malloc(len + 1);
    if (!buf) return;
    memcpy(buf, src, len);
    buf[len] = '\0';
    size_t i = 0;
    while (i < len) {
        char *rec = buf + i;
        size_t k = strlen(rec);
        char *a = strchr(rec, '\x1f');
        char *b = a ? strchr(a + 1, '\x1f') : NULL;
        if (a && b) {
            *a = *b = '\0';
            log_to(c->logger, c->env, c->name, (fmi2Status)atoi(rec), a + 1, b + 1);
        }
        i += k + 1;
    }
    free(buf);
}

/* ---------------------------------------------------------------------------------------------- */
/* the model process                                                                               */

#ifdef _WIN32
#include <windows.h>
static double now(void) {
    LARGE_INTEGER f, t;
    QueryPerformanceFrequency(&f);
    QueryPerformanceCounter(&t);
    return (double)t.QuadPart / (double)f.QuadPart;
}
#else
static double now(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}
#endif

static double env_seconds(const char *name, double dflt) {
    const char *s = getenv(name);
    if (!s || !*s) return dflt;
    char *end;
    double v = strtod(s, &end);
    return (end != s && v > 0) ? v : dflt;
}

#ifndef _WIN32
static volatile uint32_t *word(Comp *c, unsigned off) { return (volatile uint32_t *)(c->shm + off); }

static void futex_wake(volatile uint32_t *w) { syscall(SYS_futex, (uint32_t *)w, FUTEX_WAKE, INT_MAX, NULL, NULL, 0); }

static void futex_wait(volatile uint32_t *w, uint32_t expected, double seconds) {
    struct timespec ts;
    ts.tv_sec = (time_t)seconds;
    ts.tv_nsec = (long)((seconds - (double)ts.tv_sec) * 1e9);
    syscall(SYS_futex, (uint32_t *)w, FUTEX_WAIT, expected, &ts, NULL, 0);
}

/* The last lines of the model process's stderr (at most ~3 kB). */
static void stderr_tail(Comp *c, char *out, size_t n) {
    out[0] = '\0';
    struct stat st;
    if (c->log_fd < 0 || fstat(c->log_fd, &st) != 0 || st.st_size <= 0) return;
    size_t want = n - 1 < 3072 ? n - 1 : 3072;
    off_t from = st.st_size > (off_t)want ? st.st_size - (off_t)want : 0;
    ssize_t r = pread(c->log_fd, out, (size_t)(st.st_size - from), from);
    if (r <= 0) { out[0] = '\0'; return; }
    out[r] = '\0';
    char *p = out;
    if (from > 0 && (p = strchr(out, '\n')) != NULL) memmove(out, p + 1, strlen(p + 1) + 1);
    size_t k = strlen(out);
    while (k && (out[k - 1] == '\n' || out[k - 1] == ' ')) out[--k] = '\0';
}

#else
static void stderr_tail(Comp *c, char *out, size_t n) { (void)c; if (n) out[0] = '\0'; }
#endif

/* The model process is gone or useless: kill and reap it, log why, refuse every later call. */
static void fail(Comp *c, const char *why) {
#ifndef _WIN32
    if (c->pid > 0) {
        kill(c->pid, SIGKILL);
        while (waitpid(c->pid, NULL, 0) < 0 && errno == EINTR) {}
        c->pid = 0;
    }
#endif
    char tail[3200];
    stderr_tail(c, tail, sizeof tail);
    mlog(c, fmi2Error, "%s%s%s%s", why, c->seq > 1 ? "; every later call returns fmi2Error (instantiate anew)" : "",
         *tail ? ". Last output of the model process:\n" : "", tail);
    c->dead = 1;
}

#ifndef _WIN32
static void describe_exit(int status, char *out, size_t n) {
    if (WIFEXITED(status)) snprintf(out, n, "the model process exited with status %d", WEXITSTATUS(status));
    else if (WIFSIGNALED(status))
        snprintf(out, n, "the model process was killed by signal %d (%s)", WTERMSIG(status), strsignal(WTERMSIG(status)));
    else snprintf(out, n, "the model process ended (wait status %d)", status);
}

/* Waiting for the model process. A thread woken from a futex waits for the scheduler: tens of microseconds on
 * a quiet machine, more on a virtual machine whose idle processor must first be woken. So the master spins
 * while the answer is due, and sleeps otherwise:
 *  - every call: a short spin (SPIN_SHORT) first; for a step the model process answered within SPIN_SHORT_STEP
 *    last time, 2 x that time + 100 us;
 *  - fmi2DoStep: the model process publishes the simulated time its integrator has reached (a double in the
 *    shared header, O_PROG). From the progress over the elapsed wall time the master predicts the end of the
 *    integration, sleeps on the futex (with a timeout) until SPIN_EARLY before it, then spins, at most
 *    spin_late() beyond the predicted end (learned from the model's work after its integration). Without
 *    progress (no integration) the last step's time serves as the prediction. A step that takes longer than predicted is waited for on the futex: no core burns while
 *    the model process works. */
#define SPIN_SHORT 50e-6   /* [s] */
#define SPIN_EARLY 150e-6  /* [s] */
#define SPIN_LATE 250e-6   /* [s], at least: 2 x the learned tail + 50 us, at most SPIN_LATE_MAX */
#define SPIN_LATE_MAX 1e-3 /* [s] */
#define MAX_SPINS 3        /* predicted spins per call */
#define SPIN_SHORT_STEP 300e-6 /* a step the model process answered within this is spun through: 2 x its time + 100 us [s] */

/* Spins until the response or t_end. (No sched_yield between polls: on a busy machine a yielding thread
 * waits behind every other runnable one, milliseconds, which is what the spin is to avoid.) */
static int spin_until(volatile uint32_t *resp, uint32_t seq, double t_end) {
    for (;;) {
        for (int i = 0; i < 32; i++) {
            if (__atomic_load_n(resp, __ATOMIC_ACQUIRE) == seq) return 1;
            __builtin_ia32_pause();
        }
        if (now() >= t_end) return __atomic_load_n(resp, __ATOMIC_ACQUIRE) == seq;
    }
}

/* The model's live integration time [s], NAN when it publishes none. */
static double progress(Comp *c) {
    uint32_t off;
    memcpy(&off, c->shm + O_PROG, 4);
    if (off < 128 || off + 8 > HDR || off % 8) return NAN;
    uint64_t bits = __atomic_load_n((volatile uint64_t *)(c->shm + off), __ATOMIC_RELAXED);
    double t;
    memcpy(&t, &bits, 8);
    return t;
}

/* The spin of a step near its predicted end: until the response or t_end, watching the progress too. The
 * time from the integration's end (progress at prog0 + h) to the answer is the model's work after its
 * integration (outputs, the session's Python): its running mean c->tail sets how long the master spins past
 * the predicted end, so that a slower machine's longer tail is still caught by the spin. */
static int spin_step(Comp *c, volatile uint32_t *resp, double t_end, double prog0, double h) {
    double t_int = -1.0;
    for (;;) {
        for (int i = 0; i < 32; i++) {
            if (__atomic_load_n(resp, __ATOMIC_ACQUIRE) == c->seq) {
                if (t_int >= 0.0) {
                    double d = now() - t_int;
                    c->tail = 0.8 * c->tail + 0.2 * (d < SPIN_LATE_MAX ? d : SPIN_LATE_MAX);
                }
                return 1;
            }
            __builtin_ia32_pause();
        }
        double t = now();
        if (t_int < 0.0 && isfinite(prog0) && (progress(c) - prog0) >= h * (1.0 - 1e-9)) t_int = t;
        if (t >= t_end) {
            if (__atomic_load_n(resp, __ATOMIC_ACQUIRE) == c->seq) return 1;
            /* integrated, yet no answer within the window: the tail is longer than learned, lengthen it */
            if (t_int >= 0.0) {
                double d = t - t_int + 100e-6;
                c->tail = 0.8 * c->tail + 0.2 * (d < SPIN_LATE_MAX ? d : SPIN_LATE_MAX);
            }
            return 0;
        }
    }
}

/* Waiting through a whole step. While the master sleeps its processor goes idle, and on a virtual machine an
 * idle processor halts: the master then resumes on cold caches, and its own code after the answer (fmpy's
 * doStep return and getReal) costs 30-50 us more per step than when it stays awake (measured, docs/fmu.md).
 * With BEARING_FMU_WAIT=auto the master spins through a step while a processor is idle: the machine's
 * running threads (/proc/loadavg, this one included) are no more than the processors it may use, and the
 * model process has not been kept waiting for a processor (its run delay, /proc/<pid>/schedstat, grew by
 * less than 5 % of the wall time since the last step; else no spinning for HOLD_STEPS steps); it never takes
 * a processor another thread wants. spin: always. The default, sleep, never spins through a step (the
 * predicted spin only): the saving is 1 % of a 1 ms step of the full model at most, and a master spinning
 * through every step keeps a processor busy for the whole run (docs/fmu.md). */
#define WAIT_AUTO 0
#define WAIT_SLEEP 1
#define WAIT_SPIN 2
#define HOLD_STEPS 32
#define SPIN_THROUGH_MAX 0.05 /* [s] beyond twice the expected step: then the predicted spin and the futex */
#define SPIN_THROUGH_STEP 0.2 /* [s] longer steps are not spun through (the saving is nothing against them) */

static int idle_cpu(void) {
    cpu_set_t set;
    int ncpu = sched_getaffinity(0, sizeof set, &set) == 0 ? CPU_COUNT(&set) : (int)sysconf(_SC_NPROCESSORS_ONLN);
    char buf[128];
    int fd = open("/proc/loadavg", O_RDONLY | O_CLOEXEC);
    if (fd < 0) return 0;
    ssize_t n = read(fd, buf, sizeof buf - 1);
    close(fd);
    if (n <= 0) return 0;
    buf[n] = '\0';
    double l1, l5, l15;
    int running = 0, total = 0;
    if (sscanf(buf, "%lf %lf %lf %d/%d", &l1, &l5, &l15, &running, &total) != 5) return 0;
    return running <= ncpu;
}

/* Time [s] the process pid has waited on a run queue (schedstat's second field), NAN if unknown. */
static double run_delay(pid_t pid) {
    char path[64], buf[128];
    snprintf(path, sizeof path, "/proc/%d/schedstat", (int)pid);
    int fd = open(path, O_RDONLY | O_CLOEXEC);
    if (fd < 0) return NAN;
    ssize_t n = read(fd, buf, sizeof buf - 1);
    close(fd);
    if (n <= 0) return NAN;
    buf[n] = '\0';
    unsigned long long run, delay;
    if (sscanf(buf, "%llu %llu", &run, &delay) != 2) return NAN;
    return (double)delay * 1e-9;
}

/* Whether to spin through the step now being waited for (see above). */
static int spin_through(Comp *c) {
    if (c->wait_mode == WAIT_SPIN) return 1;
    if (c->wait_mode == WAIT_SLEEP) return 0;
    double d = run_delay(c->pid), t = now();
    if (isfinite(d) && isfinite(c->delay_prev) && t > c->t_prev && d - c->delay_prev > 0.05 * (t - c->t_prev))
        c->hold = HOLD_STEPS;
    c->delay_prev = d;
    c->t_prev = t;
    if (c->hold > 0) {
        c->hold--;
        return 0;
    }
    return idle_cpu();
}

/* How long the master spins past the predicted end of an integration [s]. */
static double spin_late(const Comp *c) {
    double late = 2.0 * c->tail + 50e-6;
    return late < SPIN_LATE ? SPIN_LATE : (late > SPIN_LATE_MAX ? SPIN_LATE_MAX : late);
}

/* Seconds until the answer to a step is expected: from the integration's progress since the request
 * (prog0: the published time then, h: the step) over the wall time el since it, else from the last step. */
static double step_remaining(Comp *c, double prog0, double h, double el) {
    double p = progress(c);
    if (isfinite(p) && isfinite(prog0) && h > 0) {
        double frac = (p - prog0) / h;
        if (frac >= 1.0 - 1e-9) return 0.0;          /* integrated: the answer is due */
        if (frac > 0.02) return el * (1.0 - frac) / frac;
    }
    return c->step_expect > el ? c->step_expect - el : (el > 1e-3 ? el : 1e-3);
}

/* Waits for the response to request c->seq; 0 when it came, else the process is failed (logged). For a
 * step, h > 0 and prog0 the model's published time at the request. */
static int await(Comp *c, double timeout, const char *fname, double h, double prog0) {
    volatile uint32_t *resp = word(c, O_RESP);
    double t0 = now();
    /* A short step (a steady fidelity level, a tiny communication step) is answered in tens of microseconds:
     * the master spins through it. Sleeping there would cost two wake-ups per step: the master's and, because
     * waking a sleeping thread costs the waker tens of microseconds too (an inter-processor interrupt, a VM
     * exit on a virtual machine), the model process's delay in seeing the next request. */
    double spin = SPIN_SHORT;
    /* A short step whose model process answered last from the processor this request is sent from: a
     * spinning master would hold the processor the model process needs (the scheduler's wake-up placement
     * puts a woken thread beside its waker; the model process moves away on seeing this, model_process.py),
     * so no spin: sleep. Long steps (the master sleeps through them anyway) keep the waits below. */
    int32_t wcpu;
    memcpy(&wcpu, c->shm + O_WCPU, 4);
    int shared = h > 0 && c->step_expect > 0 && c->step_expect < SPIN_SHORT_STEP && c->mcpu >= 0 &&
                 wcpu == c->mcpu;
    int long_spin = !shared && h > 0 && c->step_expect > 0 && c->step_expect < SPIN_SHORT_STEP &&
                    (c->short_score > 0.3 || (c->seq & 15u) == 0);
    if (long_spin) spin = 2.0 * c->step_expect + 100e-6;
    int hit = shared ? __atomic_load_n(resp, __ATOMIC_ACQUIRE) == c->seq : spin_until(resp, c->seq, t0 + spin);
    if (long_spin) c->short_score = 0.9 * c->short_score + (hit ? 0.1 : 0.0);
    if (hit) {
        if (h > 0) c->n_wait[0]++;
        c->last_wait = 0;
        return 0;
    }
    if (shared) c->n_shared++;
    if (!shared && h > 0 && c->step_expect < SPIN_THROUGH_STEP && spin_through(c)) {
        double lim = now() + (c->step_expect > 0 ? 2.0 * c->step_expect : 0.0) + SPIN_THROUGH_MAX;
        if (spin_step(c, resp, lim, prog0, h)) {
            c->n_wait[3]++;
            c->last_wait = 3;
            return 0;
        }
    }
    /* predicted spins only while they pay: on a machine with more runnable threads than cores the progress
     * is erratic and a spinning master takes a core from the model process; then every 16th step probes */
    int spins = !shared && h > 0 && (c->spin_score > 0.3 || (c->seq & 15u) == 0) ? MAX_SPINS : 0;
    for (;;) {
        uint32_t v = __atomic_load_n(resp, __ATOMIC_ACQUIRE);
        if (v == c->seq) return 0;
        double nap = 0.1;
        if (spins > 0) {
            double t = now();
            double rem = step_remaining(c, prog0, h, t - t0);
            if (rem <= SPIN_EARLY) {
                spins--;
                if (spin_step(c, resp, t + rem + spin_late(c), prog0, h)) {
                    c->spin_score = 0.9 * c->spin_score + 0.1;
                    c->n_wait[1]++;
                    c->last_wait = 1;
                    return 0;
                }
                /* predicted too early: predict again from the progress now (a nap or another spin) */
                if (spins > 0 && step_remaining(c, prog0, h, now() - t0) > 0.0) continue;
                /* integrated but not answered within the late spin (or out of spins): sleep until woken */
                c->spin_score *= 0.9;
                spins = 0;
            } else {
                /* nap at most half the predicted time, then predict again from the progress made */
                double n = rem - SPIN_EARLY < 0.5 * rem ? rem - SPIN_EARLY : 0.5 * rem;
                if (n < nap) nap = n;
            }
            v = __atomic_load_n(resp, __ATOMIC_ACQUIRE);
            if (v == c->seq) return 0;
        }
        futex_wait(resp, v, nap);
        if (__atomic_load_n(resp, __ATOMIC_ACQUIRE) == c->seq) {
            if (spins > 0) c->spin_score *= 0.9;   /* answered while the master slept: predicted too late */
            if (h > 0) c->n_wait[2]++;
            c->last_wait = 2;
            return 0;
        }
        int status;
        pid_t r = waitpid(c->pid, &status, WNOHANG);
        if (r == c->pid || (r < 0 && errno == ECHILD)) {
            char why[512], msg[700];
            if (r == c->pid) describe_exit(status, why, sizeof why);
            else snprintf(why, sizeof why, "the model process ended (reaped by another part of the master)");
            c->pid = 0;
            snprintf(msg, sizeof msg, "%s: %s", fname, why);
            fail(c, msg);
            return -1;
        }
        if (now() - t0 > timeout) {
            char msg[700];
            snprintf(msg, sizeof msg, "%s: the model process (pid %d) did not answer within %g s (stopped or hung; "
                     "limit: BEARING_FMU_%s_TIMEOUT); it was killed", fname, (int)c->pid, timeout,
                     timeout == c->step_timeout ? "STEP" : "INIT");
            fail(c, msg);
            return -1;
        }
    }
}

#endif /* the local model process's wait */

/* Request area: the pending inputs, then the command's payload. */
static unsigned char *req_begin(Comp *c) {
    unsigned char *p = c->shm + HDR;
    uint32_t n = (uint32_t)c->npending;
    memcpy(p, &n, 4);
    p += 4;
    for (int k = 0; k < c->npending; k++) memcpy(p + 4 * k, &c->vars[c->pending[k]].vr, 4);
    p += 4 * n;
    for (int k = 0; k < c->npending; k++) {
        Var *v = &c->vars[c->pending[k]];
        double x = v->type == T_REAL ? v->r : (double)v->i;
        memcpy(p + 8 * k, &x, 8);
        v->dirty = 0;
    }
    c->npending = 0;
    return p + 8 * n;
}

static const size_t REQ_CAP = (SHM_SIZE - HDR) / 2;
static unsigned char *resp_area(Comp *c) { return c->shm + HDR + (SHM_SIZE - HDR) / 2; }

/* The exchange with a model server's process (bearing_tcp.c): the request bytes out, the response's header
 * fields into this layer's private copy of the shared-memory header and its bytes into the response area, so
 * that the rest of the layer reads them as from a local model process. 0, or -1 with the instance failed. */
static int tcp_round(Comp *c, uint32_t cmd, size_t len, double timeout, const char *fname) {
    BTcpHead h;
    size_t blen = 0;
    char err[4096], msg[4400];
    c->seq++;
    int r = btcp_call(c->tcp, cmd, c->shm + HDR, len, &h, resp_area(c), REQ_CAP, &blen, timeout, err, sizeof err);
    if (r != 0) {
        if (r == -2)
            snprintf(msg, sizeof msg, "%s: the model server at %s did not answer within %g s (its model process "
                     "stopped or hung, or the network failed; limit: BEARING_FMU_%s_TIMEOUT); the connection was "
                     "closed", fname, btcp_peer(c->tcp), timeout, timeout == c->step_timeout ? "STEP" : "INIT");
        else
            snprintf(msg, sizeof msg, "%s: %s", fname, err);
        btcp_close(c->tcp);
        c->tcp = NULL;
        fail(c, msg);
        return -1;
    }
    uint64_t rl = blen;
    memcpy(c->shm + O_STATUS, &h.status, 4);
    memcpy(c->shm + O_MODE, &h.mode, 4);
    memcpy(c->shm + O_FLAGS, &h.flags, 4);
    memcpy(c->shm + O_RESPLEN, &rl, 8);
    memcpy(c->shm + O_TIME, &h.time, 8);
    memcpy(c->shm + O_BUSY, &h.busy, 8);
    return 0;
}

/* Sends the request ending at `end`, waits, returns the status (fmi2Error if the process failed). Sets
 * body and blen to the response body after the log records (general layout). */
static fmi2Status exchange(Comp *c, uint32_t cmd, unsigned char *end, double timeout, const char *fname,
                           const unsigned char **body, size_t *blen) {
    uint64_t len = (uint64_t)(end - (c->shm + HDR));
    double t_send = 0.0;
    if (c->remote) {
        if (!c->tcp) return fmi2Error;
        t_send = now();
        if (tcp_round(c, cmd, (size_t)len, timeout, fname) != 0) return fmi2Error;
    } else {
#ifndef _WIN32
    memcpy(c->shm + O_REQLEN, &len, 8);
    memcpy(c->shm + O_CMD, &cmd, 4);
    double prog0 = cmd == C_STEP ? progress(c) : NAN;
    c->mcpu = sched_getcpu();
    int32_t mcpu = c->mcpu;
    memcpy(c->shm + O_MCPU, &mcpu, 4);
    t_send = now();
    __atomic_store_n(word(c, O_REQ), ++c->seq, __ATOMIC_RELEASE);
    futex_wake(word(c, O_REQ));
    if (await(c, timeout, fname, cmd == C_STEP ? c->step_h : 0.0, prog0) != 0) return fmi2Error;
#endif
    }
    double t_seen = now();
    int32_t st;
    uint32_t mode;
    uint64_t rlen;
    memcpy(&st, c->shm + O_STATUS, 4);
    memcpy(&mode, c->shm + O_MODE, 4);
    memcpy(&rlen, c->shm + O_RESPLEN, 8);
    memcpy(&c->time, c->shm + O_TIME, 8);
    memcpy(&c->busy, c->shm + O_BUSY, 8);
    if (cmd == C_STEP) {
        c->step_expect = c->busy;
        double ex = (t_seen - t_send - c->busy) * 1e6;
        int b = ex < 10 ? 0 : ex < 20 ? 1 : ex < 40 ? 2 : ex < 80 ? 3 : 4;
        c->ex_hist[c->last_wait][b]++;
    }
    c->mode = (int)mode;
    if (cmd != C_STEP) {
        const unsigned char *r = resp_area(c);
        uint32_t nlog;
        memcpy(&nlog, r, 4);
        emit_logs(c, r + 4, nlog);
        if (body) *body = r + 4 + nlog;
        if (blen) *blen = rlen - 4 - nlog;
    }
    if (st < fmi2OK || st > fmi2Fatal) st = fmi2Error;
    return (fmi2Status)st;
}

static uint32_t rd_u32(const unsigned char **p) { uint32_t v; memcpy(&v, *p, 4); *p += 4; return v; }
static int32_t rd_i32(const unsigned char **p) { int32_t v; memcpy(&v, *p, 4); *p += 4; return v; }
static double rd_f64(const unsigned char **p) { double v; memcpy(&v, *p, 8); *p += 8; return v; }
static char *rd_str(const unsigned char **p) {
    uint32_t n = rd_u32(p);
    char *s = (char *)malloc(n + 1);
    if (s) { memcpy(s, *p, n); s[n] = '\0'; }
    *p += n;
    return s;
}
static unsigned char *wr_u32(unsigned char *p, uint32_t v) { memcpy(p, &v, 4); return p + 4; }
static unsigned char *wr_i32(unsigned char *p, int32_t v) { memcpy(p, &v, 4); return p + 4; }
static unsigned char *wr_f64(unsigned char *p, double v) { memcpy(p, &v, 8); return p + 8; }
static unsigned char *wr_str(unsigned char *p, const char *s) {
    uint32_t n = (uint32_t)(s ? strlen(s) : 0);
    p = wr_u32(p, n);
    if (n) memcpy(p, s, n);
    return p + n;
}

static const unsigned char *read_snapshot(Comp *c, const unsigned char *p) {
    for (int k = 0; k < c->nvars; k++) {
        Var *v = &c->vars[k];
        if (v->type == T_REAL) v->r = rd_f64(&p);
        else if (v->type == T_STRING) { free(v->s); v->s = rd_str(&p); }
        else v->i = rd_i32(&p);
    }
    return p;
}

static int read_table(Comp *c, const unsigned char *p) {
    uint32_t n = rd_u32(&p);
    c->vars = (Var *)calloc(n ? n : 1, sizeof(Var));
    c->pending = (int *)calloc(n ? n : 1, sizeof(int));
    if (!c->vars || !c->pending) return 0;
    c->nvars = (int)n;
    unsigned maxvr = 0, maxout = 0;
    for (uint32_t k = 0; k < n; k++) {
        Var *v = &c->vars[k];
        v->vr = rd_u32(&p);
        v->type = p[0];
        v->caus = p[1];
        p += 4;
        v->out_idx = rd_i32(&p);
        v->name = rd_str(&p);
        if (v->vr > maxvr) maxvr = v->vr;
        if (v->out_idx >= 0 && (unsigned)v->out_idx + 1 > maxout) maxout = (unsigned)v->out_idx + 1;
    }
    c->nvr = maxvr + 1;
    c->by_vr = (int *)malloc(sizeof(int) * c->nvr);
    c->out_var = (int *)malloc(sizeof(int) * (maxout ? maxout : 1));
    if (!c->by_vr || !c->out_var) return 0;
    for (unsigned k = 0; k < c->nvr; k++) c->by_vr[k] = -1;
    for (unsigned k = 0; k < maxout; k++) c->out_var[k] = -1;
    c->nout = (int)maxout;
    for (int k = 0; k < c->nvars; k++) {
        c->by_vr[c->vars[k].vr] = k;
        if (c->vars[k].out_idx >= 0) c->out_var[c->vars[k].out_idx] = k;
    }
    read_snapshot(c, p);
    return 1;
}

#ifndef _WIN32
static int spawn_model(Comp *c, const char *res, char *err, size_t nerr) {
    int shm = (int)syscall(SYS_memfd_create, "bearing_fmu_shm", MFD_CLOEXEC);
    int logfd = (int)syscall(SYS_memfd_create, "bearing_fmu_stderr", MFD_CLOEXEC);
    if (shm < 0 || logfd < 0) {
        snprintf(err, nerr, "memfd_create failed: %s", strerror(errno));
        if (shm >= 0) close(shm);
        if (logfd >= 0) close(logfd);
        return 0;
    }
    /* away from 0..3, so that the child's dup2 onto 1, 2 and 3 always clears close-on-exec */
    int s2 = fcntl(shm, F_DUPFD_CLOEXEC, 10), l2 = fcntl(logfd, F_DUPFD_CLOEXEC, 10);
    close(shm);
    close(logfd);
    c->log_fd = l2;
    if (s2 < 0 || l2 < 0 || ftruncate(s2, SHM_SIZE) != 0) {
        snprintf(err, nerr, "cannot size the shared memory: %s", strerror(errno));
        if (s2 >= 0) close(s2);
        return 0;
    }
    void *m = mmap(NULL, SHM_SIZE, PROT_READ | PROT_WRITE, MAP_SHARED, s2, 0);
    if (m == MAP_FAILED) {
        snprintf(err, nerr, "cannot map the shared memory: %s", strerror(errno));
        close(s2);
        return 0;
    }
    c->shm = (unsigned char *)m;
    uint32_t magic = SHM_MAGIC, ver = PROTOCOL;
    memcpy(c->shm + O_MAGIC, &magic, 4);
    memcpy(c->shm + O_VERSION, &ver, 4);
    int32_t nocpu = -1;
    memcpy(c->shm + O_MCPU, &nocpu, 4);
    memcpy(c->shm + O_WCPU, &nocpu, 4);

    char launcher[4200], script[4200], fdarg[16], pidarg[32];
    snprintf(launcher, sizeof launcher, "%s/launch.sh", res);
    snprintf(script, sizeof script, "%s/model_process.py", res);
    snprintf(fdarg, sizeof fdarg, "3");
    snprintf(pidarg, sizeof pidarg, "%d", (int)getpid());
    char *argv[] = {"/bin/sh", launcher, script, (char *)res, fdarg, pidarg, NULL};
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_addopen(&fa, 0, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_adddup2(&fa, l2, 1);
    posix_spawn_file_actions_adddup2(&fa, l2, 2);
    posix_spawn_file_actions_adddup2(&fa, s2, 3);
    posix_spawnattr_t at;
    posix_spawnattr_init(&at);
    sigset_t none, all;
    sigemptyset(&none);
    sigfillset(&all);
    posix_spawnattr_setsigmask(&at, &none);
    posix_spawnattr_setsigdefault(&at, &all);
    posix_spawnattr_setflags(&at, POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF);
    pid_t pid;
    int rc = posix_spawn(&pid, "/bin/sh", &fa, &at, argv, environ);
    posix_spawn_file_actions_destroy(&fa);
    posix_spawnattr_destroy(&at);
    close(s2); /* the mapping stays */
    if (rc != 0) {
        snprintf(err, nerr, "cannot start /bin/sh %s: %s", launcher, strerror(rc));
        return 0;
    }
    c->pid = pid;
    return 1;
}

/* fmuResourceLocation (file URI) -> local path; NULL/empty: <this library>/../../resources. */
static int resource_dir(const char *uri, char *out, size_t n) {
    if (uri && *uri) {
        const char *p = uri;
        if (strncmp(p, "file://localhost/", 17) == 0) p += 16;
        else if (strncmp(p, "file:///", 8) == 0) p += 7;
        else if (strncmp(p, "file:/", 6) == 0) p += 5;
        else if (strncmp(p, "file:", 5) == 0) return 0;
        size_t k = 0;
        while (*p && k + 1 < n) {
            if (p[0] == '%' && p[1] && p[2]) {
                char hex[3] = {p[1], p[2], 0};
                out[k++] = (char)strtol(hex, NULL, 16);
                p += 3;
            } else {
                out[k++] = *p++;
            }
        }
        out[k] = '\0';
        while (k > 1 && out[k - 1] == '/') out[--k] = '\0';
        return k > 0;
    }
    Dl_info info;
    if (!dladdr((void *)&resource_dir, &info) || !info.dli_fname) return 0;
    char so[4096];
    snprintf(so, sizeof so, "%s", info.dli_fname);
    for (int up = 0; up < 3; up++) { /* strip <file>, <platform>, binaries */
        char *s = strrchr(so, '/');
        if (!s) return 0;
        *s = '\0';
    }
    snprintf(out, n, "%s/resources", so);
    return 1;
}

#endif /* the local model process */

/* A model server's process for this instance (BEARING_FMU_SERVER): the handshake, and a private buffer in the
 * layout of the shared memory. */
static int connect_server(Comp *c, const char *server, const char *guid, char *err, size_t nerr) {
    c->remote = 1;
    c->shm = (unsigned char *)btcp_buffer(SHM_SIZE);
    if (!c->shm) {
        snprintf(err, nerr, "out of memory");
        return 0;
    }
    uint32_t magic = SHM_MAGIC, ver = PROTOCOL;
    memcpy(c->shm + O_MAGIC, &magic, 4);
    memcpy(c->shm + O_VERSION, &ver, 4);
    const char *token = getenv("BEARING_FMU_TOKEN");
    char why[4200];
    c->tcp = btcp_connect(server, token && *token ? token : NULL, PROTOCOL, guid ? guid : "", c->init_timeout, why,
                          sizeof why);
    if (!c->tcp) {
        if (strncmp(why, "cannot connect", 14) == 0) /* no server there: how to start one */
            snprintf(err, nerr, "%s. Start the model server on Linux with `bearing serve` (from Windows: `wsl "
                     "bearing serve`), or set BEARING_FMU_SERVER=host:port (and BEARING_FMU_TOKEN) to reach another "
                     "one", why);
        else
            snprintf(err, nerr, "%s", why);
        return 0;
    }
    return 1;
}

static void free_comp(Comp *c) {
    if (c->tcp) btcp_close(c->tcp);
    c->tcp = NULL;
    if (c->remote) btcp_buffer_free(c->shm, SHM_SIZE);
#ifndef _WIN32
    else if (c->shm) munmap(c->shm, SHM_SIZE);
    if (c->log_fd >= 0) close(c->log_fd);
#endif
    for (int k = 0; k < c->nvars; k++) {
        free(c->vars[k].s);
        free(c->vars[k].name);
    }
    for (size_t k = 0; k < c->nstrs; k++) free(c->strs[k]);
    free(c->strs);
    free(c->vars);
    free(c->pending);
    free(c->by_vr);
    free(c->out_var);
    free(c->ser);
    free(c->name);
    c->magic = 0;
    free(c);
}

/* ---------------------------------------------------------------------------------------------- */
/* FMI 2.0 API                                                                                      */

#define COMP(comp)                                                 \
    Comp *c = (Comp *)(comp);                                      \
    if (!c || c->magic != MODEL_MAGIC) return fmi2Error;           \
    if (c->dead) {                                                 \
        mlog(c, fmi2Error, "%s: the model process has ended", __func__); \
        return fmi2Error;                                          \
    }

FMI2_EXPORT const char *fmi2GetTypesPlatform(void) { return "default"; }
FMI2_EXPORT const char *fmi2GetVersion(void) { return "2.0"; }

FMI2_EXPORT fmi2Component fmi2Instantiate(fmi2String instanceName, fmi2Type fmuType, fmi2String fmuGUID,
                                          fmi2String fmuResourceLocation, const fmi2CallbackFunctions *functions,
                                          fmi2Boolean visible, fmi2Boolean loggingOn) {
    fmi2CallbackLogger logger = functions ? functions->logger : NULL;
    fmi2ComponentEnvironment env = functions ? functions->componentEnvironment : NULL;
    if (fmuType != fmi2CoSimulation) {
        log_to(logger, env, instanceName, fmi2Error, "logError", "this FMU supports co-simulation only");
        return NULL;
    }
    const char *server = getenv("BEARING_FMU_SERVER");
#ifdef _WIN32
    if (!server || !*server) server = BTCP_DEFAULT_SERVER;
#else
    char res[4096];
    if ((!server || !*server) && !resource_dir(fmuResourceLocation, res, sizeof res)) {
        char msg[4300];
        snprintf(msg, sizeof msg, "cannot use fmuResourceLocation '%s' (a file: URI is required)",
                 fmuResourceLocation ? fmuResourceLocation : "(null)");
        log_to(logger, env, instanceName, fmi2Error, "logError", msg);
        return NULL;
    }
#endif
    (void)fmuResourceLocation;
    Comp *c = (Comp *)calloc(1, sizeof(Comp));
    if (!c) return NULL;
    c->log_fd = -1;
    c->logger = logger;
    c->env = env;
    c->name = strdup(instanceName ? instanceName : "");
    c->magic = MODEL_MAGIC;
    c->spin_score = 1.0;
    c->short_score = 1.0;
    c->mcpu = -1;
    c->tail = 100e-6;
#ifndef _WIN32
    {
        const char *w = getenv("BEARING_FMU_WAIT");
        c->wait_mode = w && !strcmp(w, "auto") ? WAIT_AUTO : w && !strcmp(w, "spin") ? WAIT_SPIN : WAIT_SLEEP;
        c->delay_prev = NAN;
    }
#endif
    c->init_timeout = env_seconds("BEARING_FMU_INIT_TIMEOUT", 900.0);
    c->step_timeout = env_seconds("BEARING_FMU_STEP_TIMEOUT", 600.0);
    char err[8800];
    if (!c->name) {
        free_comp(c);
        return NULL;
    }
    if (server && *server) {
        if (!connect_server(c, server, fmuGUID, err, sizeof err)) {
            mlog(c, fmi2Error, "fmi2Instantiate: %s", err);
            free_comp(c);
            return NULL;
        }
    }
#ifndef _WIN32
    else if (!spawn_model(c, res, err, sizeof err)) {
        mlog(c, fmi2Error, "fmi2Instantiate: cannot start the model process: %s", err);
        free_comp(c);
        return NULL;
    }
#endif
    unsigned char *p = req_begin(c);
    p = wr_str(p, fmuGUID ? fmuGUID : "");
    p = wr_str(p, c->name);
    p = wr_i32(p, visible);
    p = wr_i32(p, loggingOn);
    const unsigned char *body;
    size_t blen;
    fmi2Status st = exchange(c, C_HELLO, p, c->init_timeout, "fmi2Instantiate", &body, &blen);
    if (!c->dead && st <= fmi2Warning && !read_table(c, body)) {
        mlog(c, fmi2Error, "fmi2Instantiate: out of memory");
        st = fmi2Error;
    }
    if (st > fmi2Warning) {
#ifndef _WIN32
        if (!c->dead && c->pid > 0) { /* the model refused (GUID ...): it exits by itself */
            for (int k = 0; k < 100 && waitpid(c->pid, NULL, WNOHANG) == 0; k++) usleep(10000);
            kill(c->pid, SIGKILL);
            waitpid(c->pid, NULL, WNOHANG);
            c->pid = 0;
        }
#endif
        free_comp(c);
        return NULL;
    }
    return (fmi2Component)c;
}

FMI2_EXPORT void fmi2FreeInstance(fmi2Component comp) {
    Comp *c = (Comp *)comp;
    if (!c || c->magic != MODEL_MAGIC) return;
    if (getenv("BEARING_FMU_WAIT_STATS"))   /* how the master saw the step answers (bench/bench_fmu.py) */
    {
        fprintf(stderr, "BEARING_FMU_WAIT_STATS first_spin=%lu predicted_spin=%lu asleep=%lu spun_through=%lu "
                "tail_us=%.1f same_processor=%lu\n", c->n_wait[0], c->n_wait[1], c->n_wait[2], c->n_wait[3],
                c->tail * 1e6, c->n_shared);
        for (int k = 0; k < 4; k++)
            fprintf(stderr, "BEARING_FMU_EXCHANGE_HIST %d %lu %lu %lu %lu %lu\n", k, c->ex_hist[k][0],
                    c->ex_hist[k][1], c->ex_hist[k][2], c->ex_hist[k][3], c->ex_hist[k][4]);
    }
    if (!c->dead && (c->pid > 0 || c->tcp)) {
        unsigned char *p = req_begin(c);
        exchange(c, C_FREE, p, c->remote && c->step_timeout < 30.0 ? c->step_timeout : 30.0, "fmi2FreeInstance",
                 NULL, NULL);
    }
#ifndef _WIN32
    if (c->pid > 0) { /* it exits after answering; a bounded wait, then kill */
        int reaped = 0;
        for (int k = 0; k < 500 && !reaped; k++) {
            pid_t r = waitpid(c->pid, NULL, WNOHANG);
            if (r == c->pid || (r < 0 && errno != EINTR)) reaped = 1;
            else usleep(2000);
        }
        if (!reaped) {
            kill(c->pid, SIGKILL);
            while (waitpid(c->pid, NULL, 0) < 0 && errno == EINTR) {}
        }
        c->pid = 0;
    }
#endif
    free_comp(c);
}

static fmi2Status simple(fmi2Component comp, uint32_t cmd, const char *fname) {
    COMP(comp);
    unsigned char *p = req_begin(c);
    return exchange(c, cmd, p, c->init_timeout, fname, NULL, NULL);
}

FMI2_EXPORT fmi2Status fmi2SetDebugLogging(fmi2Component comp, fmi2Boolean on, size_t n, const fmi2String cats[]) {
    COMP(comp);
    unsigned char *p = req_begin(c);
    p = wr_i32(p, on);
    p = wr_i32(p, (int32_t)n);
    for (size_t k = 0; k < n; k++) p = wr_str(p, cats[k]);
    return exchange(c, C_DEBUG, p, c->init_timeout, "fmi2SetDebugLogging", NULL, NULL);
}

FMI2_EXPORT fmi2Status fmi2SetupExperiment(fmi2Component comp, fmi2Boolean tolDefined, fmi2Real tol, fmi2Real start,
                                           fmi2Boolean stopDefined, fmi2Real stop) {
    COMP(comp);
    unsigned char *p = req_begin(c);
    p = wr_i32(p, tolDefined);
    p = wr_f64(p, tol);
    p = wr_f64(p, start);
    p = wr_f64(p, stop);
    p = wr_i32(p, stopDefined);
    return exchange(c, C_SETUP, p, c->init_timeout, "fmi2SetupExperiment", NULL, NULL);
}

FMI2_EXPORT fmi2Status fmi2EnterInitializationMode(fmi2Component c) {
    return simple(c, C_ENTER, "fmi2EnterInitializationMode");
}

FMI2_EXPORT fmi2Status fmi2ExitInitializationMode(fmi2Component comp) {
    COMP(comp);
    unsigned char *p = req_begin(c);
    const unsigned char *body;
    size_t blen;
    fmi2Status st = exchange(c, C_EXIT, p, c->init_timeout, "fmi2ExitInitializationMode", &body, &blen);
    if (!c->dead && c->mode == M_STEP && (*(uint32_t *)(c->shm + O_FLAGS) & F_SNAPSHOT)) read_snapshot(c, body);
    return st;
}

FMI2_EXPORT fmi2Status fmi2Terminate(fmi2Component c) { return simple(c, C_TERMINATE, "fmi2Terminate"); }

FMI2_EXPORT fmi2Status fmi2Reset(fmi2Component comp) {
    COMP(comp);
    unsigned char *p = req_begin(c);
    const unsigned char *body;
    size_t blen;
    fmi2Status st = exchange(c, C_RESET, p, c->init_timeout, "fmi2Reset", &body, &blen);
    if (!c->dead && (*(uint32_t *)(c->shm + O_FLAGS) & F_SNAPSHOT)) read_snapshot(c, body);
    return st;
}

/* ---- variables ---- */

static Var *local_var(Comp *c, fmi2ValueReference vr, int type) {
    if (vr >= c->nvr || c->by_vr[vr] < 0) return NULL;
    Var *v = &c->vars[c->by_vr[vr]];
    return v->type == type ? v : NULL;
}

/* Forwarded fmi2Get*: the model checks and answers; values at *body. */
static fmi2Status get_remote(Comp *c, int type, const fmi2ValueReference vr[], size_t n, const unsigned char **body,
                             const char *fname) {
    unsigned char *p = req_begin(c);
    p = wr_u32(p, (uint32_t)type);
    p = wr_u32(p, (uint32_t)n);
    for (size_t k = 0; k < n; k++) p = wr_u32(p, vr[k]);
    size_t blen;
    return exchange(c, C_GET, p, c->init_timeout, fname, body, &blen);
}

/* Served here in step mode when every reference is known with this type (outputs from the last step). */
static int local_get_ok(Comp *c, int type, const fmi2ValueReference vr[], size_t n) {
    if (c->mode != M_STEP) return 0;
    for (size_t k = 0; k < n; k++) {
        Var *v = local_var(c, vr[k], type);
        if (!v || (v->caus == CAUS_OUTPUT && v->out_idx < 0)) return 0;
    }
    return 1;
}

FMI2_EXPORT fmi2Status fmi2GetReal(fmi2Component comp, const fmi2ValueReference vr[], size_t n, fmi2Real v[]) {
    COMP(comp);
    if (local_get_ok(c, T_REAL, vr, n)) {
        for (size_t k = 0; k < n; k++) v[k] = c->vars[c->by_vr[vr[k]]].r;
        return fmi2OK;
    }
    const unsigned char *b;
    fmi2Status st = get_remote(c, T_REAL, vr, n, &b, "fmi2GetReal");
    if (st <= fmi2Warning && !c->dead)
        for (size_t k = 0; k < n; k++) v[k] = rd_f64(&b);
    return st;
}

static fmi2Status get_int(Comp *comp, int type, const fmi2ValueReference vr[], size_t n, int v[], const char *fname) {
    COMP(comp);
    if (local_get_ok(c, type, vr, n)) {
        for (size_t k = 0; k < n; k++) v[k] = c->vars[c->by_vr[vr[k]]].i;
        return fmi2OK;
    }
    const unsigned char *b;
    fmi2Status st = get_remote(c, type, vr, n, &b, fname);
    if (st <= fmi2Warning && !c->dead)
        for (size_t k = 0; k < n; k++) v[k] = rd_i32(&b);
    return st;
}

FMI2_EXPORT fmi2Status fmi2GetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t n, fmi2Integer v[]) {
    return get_int((Comp *)c, T_INTEGER, vr, n, v, "fmi2GetInteger");
}
FMI2_EXPORT fmi2Status fmi2GetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t n, fmi2Boolean v[]) {
    return get_int((Comp *)c, T_BOOLEAN, vr, n, v, "fmi2GetBoolean");
}

FMI2_EXPORT fmi2Status fmi2GetString(fmi2Component comp, const fmi2ValueReference vr[], size_t n, fmi2String v[]) {
    COMP(comp);
    if (local_get_ok(c, T_STRING, vr, n)) {
        for (size_t k = 0; k < n; k++) v[k] = c->vars[c->by_vr[vr[k]]].s;
        return fmi2OK;
    }
    const unsigned char *b;
    fmi2Status st = get_remote(c, T_STRING, vr, n, &b, "fmi2GetString");
    if (st <= fmi2Warning && !c->dead) {
        for (size_t k = 0; k < c->nstrs; k++) free(c->strs[k]);
        free(c->strs);
        c->strs = (char **)calloc(n ? n : 1, sizeof(char *));
        c->nstrs = c->strs ? n : 0;
        for (size_t k = 0; k < c->nstrs; k++) v[k] = c->strs[k] = rd_str(&b);
    }
    return st;
}

/* Inputs in step mode are kept here and travel with the next exchange; anything else goes to the model. */
static int local_set_ok(Comp *c, int type, const fmi2ValueReference vr[], size_t n) {
    if (c->mode != M_STEP || type == T_STRING) return 0;
    for (size_t k = 0; k < n; k++) {
        Var *v = local_var(c, vr[k], type);
        if (!v || v->caus != CAUS_INPUT) return 0;
    }
    return 1;
}

static void set_local(Comp *c, fmi2ValueReference vr, double r, int i) {
    int idx = c->by_vr[vr];
    Var *v = &c->vars[idx];
    if (v->type == T_REAL) v->r = r;
    else v->i = i;
    if (!v->dirty) {
        v->dirty = 1;
        c->pending[c->npending++] = idx;
    }
}

static fmi2Status set_remote(Comp *c, int type, const fmi2ValueReference vr[], size_t n, const void *vals,
                             const char *fname) {
    unsigned char *p = req_begin(c);
    if ((size_t)(p - (c->shm + HDR)) + 16 + n * 16 > REQ_CAP) {
        mlog(c, fmi2Error, "%s: %zu values do not fit one request", fname, n);
        return fmi2Error;
    }
    p = wr_u32(p, (uint32_t)type);
    p = wr_u32(p, (uint32_t)n);
    for (size_t k = 0; k < n; k++) p = wr_u32(p, vr[k]);
    for (size_t k = 0; k < n; k++) {
        if (type == T_REAL) p = wr_f64(p, ((const double *)vals)[k]);
        else if (type == T_STRING) p = wr_str(p, ((const fmi2String *)vals)[k]);
        else p = wr_i32(p, ((const int *)vals)[k]);
    }
    fmi2Status st = exchange(c, C_SET, p, c->init_timeout, fname, NULL, NULL);
    if (st <= fmi2Warning && !c->dead) /* keep this layer's copy in step with what the model accepted */
        for (size_t k = 0; k < n; k++) {
            if (vr[k] >= c->nvr || c->by_vr[vr[k]] < 0) continue;
            Var *v = &c->vars[c->by_vr[vr[k]]];
            if (v->type != type) continue;
            if (type == T_REAL) v->r = ((const double *)vals)[k];
            else if (type == T_STRING) { free(v->s); v->s = strdup(((const fmi2String *)vals)[k] ? ((const fmi2String *)vals)[k] : ""); }
            else v->i = ((const int *)vals)[k];
        }
    return st;
}

FMI2_EXPORT fmi2Status fmi2SetReal(fmi2Component comp, const fmi2ValueReference vr[], size_t n, const fmi2Real v[]) {
    COMP(comp);
    if (local_set_ok(c, T_REAL, vr, n)) {
        for (size_t k = 0; k < n; k++) set_local(c, vr[k], v[k], 0);
        return fmi2OK;
    }
    return set_remote(c, T_REAL, vr, n, v, "fmi2SetReal");
}

static fmi2Status set_int(Comp *comp, int type, const fmi2ValueReference vr[], size_t n, const int v[],
                          const char *fname) {
    COMP(comp);
    if (local_set_ok(c, type, vr, n)) {
        for (size_t k = 0; k < n; k++) set_local(c, vr[k], 0.0, type == T_BOOLEAN ? (v[k] != 0) : v[k]);
        return fmi2OK;
    }
    return set_remote(c, type, vr, n, v, fname);
}

FMI2_EXPORT fmi2Status fmi2SetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t n, const fmi2Integer v[]) {
    return set_int((Comp *)c, T_INTEGER, vr, n, v, "fmi2SetInteger");
}
FMI2_EXPORT fmi2Status fmi2SetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t n, const fmi2Boolean v[]) {
    return set_int((Comp *)c, T_BOOLEAN, vr, n, v, "fmi2SetBoolean");
}
FMI2_EXPORT fmi2Status fmi2SetString(fmi2Component comp, const fmi2ValueReference vr[], size_t n, const fmi2String v[]) {
    COMP(comp);
    return set_remote(c, T_STRING, vr, n, v, "fmi2SetString");
}

/* ---- co-simulation ---- */

FMI2_EXPORT fmi2Status fmi2DoStep(fmi2Component comp, fmi2Real t, fmi2Real h, fmi2Boolean noSetFMUStatePriorToCurrentPoint) {
    COMP(comp);
    unsigned char *p = req_begin(c);
    p = wr_f64(p, t);
    p = wr_f64(p, h);
    p = wr_i32(p, noSetFMUStatePriorToCurrentPoint);
    c->step_h = h;
    fmi2Status st = exchange(c, C_STEP, p, c->step_timeout, "fmi2DoStep", NULL, NULL);
    if (c->dead) return fmi2Error;
    const unsigned char *r = resp_area(c);
    uint32_t n;
    memcpy(&n, r, 4);
    const unsigned char *o = r + 16;
    for (uint32_t k = 0; k < n; k++) {
        double x = rd_f64(&o);
        if ((int)k < c->nout && c->out_var[k] >= 0) {
            Var *v = &c->vars[c->out_var[k]];
            if (v->type == T_REAL) v->r = x;
            else v->i = (int)x;
        }
    }
    uint32_t nlog = rd_u32(&o);
    emit_logs(c, o, nlog);
    return st;
}

FMI2_EXPORT fmi2Status fmi2CancelStep(fmi2Component comp) {
    COMP(comp);
    mlog(c, fmi2Error, "fmi2CancelStep is not supported by this FMU (fmi2DoStep never returns fmi2Pending)");
    return fmi2Error;
}

static fmi2Status status_kind(Comp *c, fmi2StatusKind s, const char *what) {
    mlog(c, fmi2Discard, "status %d (%s) not available: this FMU steps synchronously (fmi2DoStep never returns "
         "fmi2Pending)", (int)s, what);
    return fmi2Discard;
}

FMI2_EXPORT fmi2Status fmi2GetStatus(fmi2Component comp, const fmi2StatusKind s, fmi2Status *v) {
    COMP(comp);
    (void)v;
    return status_kind(c, s, "status");
}
FMI2_EXPORT fmi2Status fmi2GetRealStatus(fmi2Component comp, const fmi2StatusKind s, fmi2Real *v) {
    COMP(comp);
    if (s == fmi2LastSuccessfulTime) { *v = c->time; return fmi2OK; }
    return status_kind(c, s, "real");
}
FMI2_EXPORT fmi2Status fmi2GetIntegerStatus(fmi2Component comp, const fmi2StatusKind s, fmi2Integer *v) {
    COMP(comp);
    (void)v;
    return status_kind(c, s, "integer");
}
FMI2_EXPORT fmi2Status fmi2GetBooleanStatus(fmi2Component comp, const fmi2StatusKind s, fmi2Boolean *v) {
    COMP(comp);
    if (s == fmi2Terminated) { *v = 0; return fmi2OK; }
    return status_kind(c, s, "boolean");
}
FMI2_EXPORT fmi2Status fmi2GetStringStatus(fmi2Component comp, const fmi2StatusKind s, fmi2String *v) {
    COMP(comp);
    (void)v;
    return status_kind(c, s, "string");
}

/* ---- FMU state: kept in the model process, named here by its number ---- */

FMI2_EXPORT fmi2Status fmi2GetFMUstate(fmi2Component comp, fmi2FMUstate *s) {
    COMP(comp);
    unsigned char *p = req_begin(c);
    uint64_t id = (uint64_t)(uintptr_t)*s;
    memcpy(p, &id, 8);
    const unsigned char *b;
    size_t blen;
    fmi2Status st = exchange(c, C_GETSTATE, p + 8, c->step_timeout, "fmi2GetFMUstate", &b, &blen);
    if (st <= fmi2Warning && !c->dead) {
        memcpy(&id, b, 8);
        *s = (fmi2FMUstate)(uintptr_t)id;
    }
    return st;
}

FMI2_EXPORT fmi2Status fmi2SetFMUstate(fmi2Component comp, fmi2FMUstate s) {
    COMP(comp);
    unsigned char *p = req_begin(c);
    uint64_t id = (uint64_t)(uintptr_t)s;
    memcpy(p, &id, 8);
    const unsigned char *b;
    size_t blen;
    fmi2Status st = exchange(c, C_SETSTATE, p + 8, c->step_timeout, "fmi2SetFMUstate", &b, &blen);
    if (!c->dead && (*(uint32_t *)(c->shm + O_FLAGS) & F_SNAPSHOT)) read_snapshot(c, b);
    return st;
}

FMI2_EXPORT fmi2Status fmi2FreeFMUstate(fmi2Component comp, fmi2FMUstate *s) {
    COMP(comp);
    if (!s || !*s) return fmi2OK;
    unsigned char *p = req_begin(c);
    uint64_t id = (uint64_t)(uintptr_t)*s;
    memcpy(p, &id, 8);
    fmi2Status st = exchange(c, C_FREESTATE, p + 8, c->step_timeout, "fmi2FreeFMUstate", NULL, NULL);
    if (c->ser_id == id) c->ser_id = 0;
    *s = NULL;
    return st;
}

static fmi2Status serialize_into_cache(Comp *c, fmi2FMUstate s, const char *fname) {
    uint64_t id = (uint64_t)(uintptr_t)s;
    unsigned char *p = req_begin(c);
    memcpy(p, &id, 8);
    const unsigned char *b;
    size_t blen;
    fmi2Status st = exchange(c, C_SERIALIZE, p + 8, c->step_timeout, fname, &b, &blen);
    if (st > fmi2Warning || c->dead) return c->dead ? fmi2Error : st;
    uint32_t n = rd_u32(&b);
    unsigned char *buf = (unsigned char *)malloc(n ? n : 1);
    if (!buf) { mlog(c, fmi2Error, "%s: out of memory", fname); return fmi2Error; }
    memcpy(buf, b, n);
    free(c->ser);
    c->ser = buf;
    c->ser_len = n;
    c->ser_id = id;
    return st;
}

FMI2_EXPORT fmi2Status fmi2SerializedFMUstateSize(fmi2Component comp, fmi2FMUstate s, size_t *size) {
    COMP(comp);
    fmi2Status st = serialize_into_cache(c, s, "fmi2SerializedFMUstateSize");
    if (st <= fmi2Warning) *size = c->ser_len;
    return st;
}

FMI2_EXPORT fmi2Status fmi2SerializeFMUstate(fmi2Component comp, fmi2FMUstate s, fmi2Byte b[], size_t size) {
    COMP(comp);
    if (!s || c->ser_id != (uint64_t)(uintptr_t)s) {
        fmi2Status st = serialize_into_cache(c, s, "fmi2SerializeFMUstate");
        if (st > fmi2Warning) return st;
    }
    if (size < c->ser_len) {
        mlog(c, fmi2Error, "fmi2SerializeFMUstate: size = %zu bytes is less than the state's %zu bytes "
             "(fmi2SerializedFMUstateSize)", size, c->ser_len);
        return fmi2Error;
    }
    memcpy(b, c->ser, c->ser_len);
    return fmi2OK;
}

FMI2_EXPORT fmi2Status fmi2DeSerializeFMUstate(fmi2Component comp, const fmi2Byte b[], size_t size, fmi2FMUstate *s) {
    COMP(comp);
    unsigned char *p = req_begin(c);
    if ((size_t)(p - (c->shm + HDR)) + size + 16 > REQ_CAP) {
        mlog(c, fmi2Error, "fmi2DeSerializeFMUstate: size = %zu bytes exceeds the %zu bytes of one request", size,
             REQ_CAP);
        return fmi2Error;
    }
    p = wr_u32(p, (uint32_t)size);
    memcpy(p, b, size);
    p += size;
    uint64_t id = (uint64_t)(uintptr_t)*s;
    memcpy(p, &id, 8);
    const unsigned char *r;
    size_t blen;
    fmi2Status st = exchange(c, C_DESERIALIZE, p + 8, c->step_timeout, "fmi2DeSerializeFMUstate", &r, &blen);
    if (st <= fmi2Warning && !c->dead) {
        memcpy(&id, r, 8);
        *s = (fmi2FMUstate)(uintptr_t)id;
    }
    return st;
}

static fmi2Status unsupported(fmi2Component comp, const char *what) {
    COMP(comp);
    unsigned char *p = req_begin(c);
    p = wr_str(p, what);
    return exchange(c, C_UNSUPPORTED, p, c->init_timeout, what, NULL, NULL);
}

/* ---------------------------------------------------------------------------------------------- */
/* fmi2GetDirectionalDerivative: served here from this layer's own copy of the stiffness outputs      */
/* (the outputs of the last communication point, as fmi2GetReal serves them; no model-process call).  */
/*
 * The bearing's stiffness K (outputs stiffness[i,j], i, j = 1..5; rows Fx, Fy, Fz [N], Mx, My [N m], the load on the
 * inner ring; columns dx, dy, dz [m], tx, ty [rad], its pose) is K = d(load)/d(pose) = -d(reaction)/d(pose)
 * (bearing_core.session.cosim_spec; docs/fmu.md "Stiffness and directional derivatives"). With the (unknown
 * output, known input) pairs the ModelStructure declares (reaction_Fx..My and ir_x..ir_ty on Fx..My and dx..ty):
 *   coupling = displacement (the pose dx..ty is an input):  d reaction_i / d pose_j = -K[i][j],
 *                                                           d ir_i / d pose_j = delta_ij (the pose itself);
 *   coupling = load (the loads Fx..My are inputs):           d ir_i / d load_j = (K^-1)[i][j] (the compliance),
 *                                                           d reaction_i / d load_j = -delta_ij (the steady balance
 *                                                           reaction = -load);
 * every other pair 0. K^-1 is taken over the pose's free coordinates: a coordinate whose row and column of K are
 * all zero (the tilts with fixed_tilt) has zero compliance. fmi2GetDirectionalDerivative computes
 * dvUnknown = J dvKnown with J these derivatives (FMI 2.0 section 2.1.9). Allowed after
 * fmi2ExitInitializationMode (the stiffness is that of the last communication point). */

#define DD_N 5
/* the variables it reads and serves, by name (value references are the same for every instance of this FMU,
 * so they are looked up once per process; concurrent first calls compute the same values) */
static const char *const DD_LOAD[DD_N] = {"Fx", "Fy", "Fz", "Mx", "My"};
static const char *const DD_POSE[DD_N] = {"dx", "dy", "dz", "tx", "ty"};
static const char *const DD_REAC[DD_N] = {"reaction_Fx", "reaction_Fy", "reaction_Fz", "reaction_Mx", "reaction_My"};
static const char *const DD_IR[DD_N] = {"ir_x", "ir_y", "ir_z", "ir_tx", "ir_ty"};
static struct {
    int ready;                   /* 1 once the indices below are set (atomic) */
    int load[DD_N], pose[DD_N];  /* indices into Comp.vars of the inputs */
    int reac[DD_N], ir[DD_N];    /* ... of the outputs */
    int k[DD_N * DD_N];          /* ... of stiffness[i,j], row-major */
    int coupling;                /* ... of the String parameter coupling */
} dd_ix;

static int dd_find(const Comp *c, const char *name) {
    for (int k = 0; k < c->nvars; k++)
        if (c->vars[k].name && strcmp(c->vars[k].name, name) == 0) return k;
    return -1;
}

/* The indices of dd_ix; 0 (with the missing name in *missing) if a variable is absent. */
static int dd_lookup(const Comp *c, const char **missing) {
    if (__atomic_load_n(&dd_ix.ready, __ATOMIC_ACQUIRE)) return 1;
    char name[32];
    for (int i = 0; i < DD_N; i++) {
        if ((dd_ix.load[i] = dd_find(c, DD_LOAD[i])) < 0) { *missing = DD_LOAD[i]; return 0; }
        if ((dd_ix.pose[i] = dd_find(c, DD_POSE[i])) < 0) { *missing = DD_POSE[i]; return 0; }
        if ((dd_ix.reac[i] = dd_find(c, DD_REAC[i])) < 0) { *missing = DD_REAC[i]; return 0; }
        if ((dd_ix.ir[i] = dd_find(c, DD_IR[i])) < 0) { *missing = DD_IR[i]; return 0; }
        for (int j = 0; j < DD_N; j++) {
            snprintf(name, sizeof name, "stiffness[%d,%d]", i + 1, j + 1);
            if ((dd_ix.k[DD_N * i + j] = dd_find(c, name)) < 0) { *missing = "stiffness[i,j]"; return 0; }
        }
    }
    if ((dd_ix.coupling = dd_find(c, "coupling")) < 0) { *missing = "coupling"; return 0; }
    __atomic_store_n(&dd_ix.ready, 1, __ATOMIC_RELEASE);
    return 1;
}

/* inv = A^-1 over the free coordinates of A (row and column not all zero; the others' rows and columns 0), by
 * Gauss-Jordan elimination with partial pivoting. Returns 0 if none is free or a pivot is below 1e-12 of the
 * largest entry (singular). */
static int dd_inverse(const double A[DD_N][DD_N], double inv[DD_N][DD_N]) {
    int fr[DD_N], n = 0;
    double amax = 0.0;
    for (int i = 0; i < DD_N; i++) {
        int nz = 0;
        for (int j = 0; j < DD_N; j++) {
            if (A[i][j] != 0.0 || A[j][i] != 0.0) nz = 1;
            if (fabs(A[i][j]) > amax) amax = fabs(A[i][j]);
        }
        if (nz) fr[n++] = i;
    }
    for (int i = 0; i < DD_N; i++)
        for (int j = 0; j < DD_N; j++) inv[i][j] = 0.0;
    if (n == 0) return 0;
    double a[DD_N][2 * DD_N];
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++) {
            a[i][j] = A[fr[i]][fr[j]];
            a[i][n + j] = i == j ? 1.0 : 0.0;
        }
    for (int col = 0; col < n; col++) {
        int piv = col;
        for (int r = col + 1; r < n; r++)
            if (fabs(a[r][col]) > fabs(a[piv][col])) piv = r;
        if (!(fabs(a[piv][col]) > 1e-12 * amax)) return 0;
        if (piv != col)
            for (int j = 0; j < 2 * n; j++) {
                double t = a[col][j];
                a[col][j] = a[piv][j];
                a[piv][j] = t;
            }
        double d = a[col][col];
        for (int j = 0; j < 2 * n; j++) a[col][j] /= d;
        for (int r = 0; r < n; r++) {
            if (r == col || a[r][col] == 0.0) continue;
            double f = a[r][col];
            for (int j = 0; j < 2 * n; j++) a[r][j] -= f * a[col][j];
        }
    }
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++) inv[fr[i]][fr[j]] = a[i][n + j];
    return 1;
}

static int dd_slot(const int ix[DD_N], int var) {
    for (int i = 0; i < DD_N; i++)
        if (ix[i] == var) return i;
    return -1;
}

FMI2_EXPORT fmi2Status fmi2GetDirectionalDerivative(fmi2Component comp, const fmi2ValueReference z[], size_t nz,
                                                    const fmi2ValueReference u[], size_t nu, const fmi2Real dv[],
                                                    fmi2Real df[]) {
    COMP(comp);
    const char *fname = "fmi2GetDirectionalDerivative";
    if (c->dead) {
        mlog(c, fmi2Error, "%s: the model process is gone; instantiate anew", fname);
        return fmi2Error;
    }
    if (c->mode != M_STEP) {
        mlog(c, fmi2Error, "%s: called before fmi2ExitInitializationMode; allowed after it (the stiffness is that of "
             "the last communication point)", fname);
        return fmi2Error;
    }
    if ((nz && (!z || !df)) || (nu && (!u || !dv))) {
        mlog(c, fmi2Error, "%s: a NULL array with nUnknown = %zu, nKnown = %zu", fname, nz, nu);
        return fmi2Error;
    }
    const char *missing = "";
    if (!dd_lookup(c, &missing)) {
        mlog(c, fmi2Error, "%s: this FMU has no variable %s", fname, missing);
        return fmi2Error;
    }
    /* the knowns: Real inputs; the unknowns: Real outputs */
    for (size_t k = 0; k < nu; k++) {
        Var *v = local_var(c, u[k], T_REAL);
        if (!v || v->caus != CAUS_INPUT) {
            mlog(c, fmi2Error, "%s: vKnown_ref[%zu] = %u is not a Real input; allowed: the inputs (the derivatives "
                 "are those of the outputs reaction_Fx..My and ir_x..ir_ty with respect to Fx..My and dx..ty)",
                 fname, k, (unsigned)u[k]);
            return fmi2Error;
        }
    }
    for (size_t k = 0; k < nz; k++) {
        Var *v = local_var(c, z[k], T_REAL);
        if (!v || v->caus != CAUS_OUTPUT) {
            mlog(c, fmi2Error, "%s: vUnknown_ref[%zu] = %u is not a Real output; allowed: the outputs", fname, k,
                 (unsigned)z[k]);
            return fmi2Error;
        }
    }
    const char *cpl = c->vars[dd_ix.coupling].s;
    int disp = cpl && strcmp(cpl, "displacement") == 0;
    double K[DD_N][DD_N], C[DD_N][DD_N];
    int any = 0;
    for (int i = 0; i < DD_N; i++)
        for (int j = 0; j < DD_N; j++) {
            K[i][j] = c->vars[dd_ix.k[DD_N * i + j]].r;
            if (!isfinite(K[i][j])) {
                mlog(c, fmi2Error, "%s: stiffness[%d,%d] = %g is not finite", fname, i + 1, j + 1, K[i][j]);
                return fmi2Error;
            }
            any |= K[i][j] != 0.0;
        }
    int need_c = 0;
    if (!disp)
        for (size_t k = 0; k < nz && !need_c; k++) need_c = dd_slot(dd_ix.ir, c->by_vr[z[k]]) >= 0;
    if (need_c && !dd_inverse((const double(*)[DD_N])K, C)) {
        mlog(c, fmi2Error, "%s: the stiffness of the last communication point is %s, so the compliance d ir/d load "
             "(its inverse) does not exist%s", fname, any ? "singular" : "zero",
             any ? "" : " (fidelity map with an operating map without stiffness variables: rebuild it with "
                        "bearing build-map)");
        return fmi2Error;
    }
    for (size_t a = 0; a < nz; a++) {
        int vz = c->by_vr[z[a]];
        int ir = dd_slot(dd_ix.ir, vz), re = dd_slot(dd_ix.reac, vz);
        double acc = 0.0;
        for (size_t b = 0; b < nu; b++) {
            int vu = c->by_vr[u[b]];
            int jp = dd_slot(dd_ix.pose, vu), jl = dd_slot(dd_ix.load, vu);
            double d = 0.0;
            if (disp && jp >= 0) {
                if (re >= 0) d = -K[re][jp];
                else if (ir >= 0) d = ir == jp ? 1.0 : 0.0;
            } else if (!disp && jl >= 0) {
                if (ir >= 0) d = C[ir][jl];
                else if (re >= 0) d = re == jl ? -1.0 : 0.0;
            }
            acc += d * dv[b];
        }
        df[a] = acc;
    }
    return fmi2OK;
}
FMI2_EXPORT fmi2Status fmi2SetRealInputDerivatives(fmi2Component c, const fmi2ValueReference vr[], size_t n,
                                                   const fmi2Integer order[], const fmi2Real v[]) {
    (void)vr; (void)n; (void)order; (void)v;
    return unsupported(c, "fmi2SetRealInputDerivatives");
}
FMI2_EXPORT fmi2Status fmi2GetRealOutputDerivatives(fmi2Component c, const fmi2ValueReference vr[], size_t n,
                                                    const fmi2Integer order[], fmi2Real v[]) {
    (void)vr; (void)n; (void)order; (void)v;
    return unsupported(c, "fmi2GetRealOutputDerivatives");
}
