/* A minimal FMI 2.0 co-simulation master in C (no Python): loads an unpacked FMU's binary (dlopen on Linux,
 * LoadLibrary on Windows: binaries/linux64/<id>.so or binaries/win64/<id>.dll) and runs a command script. Used by
 * tests/test_native_host.py, tests/test_map_fmu.py (also cross-compiled with mingw-w64 and run under wine64) and
 * bench/fmu_exit_check.py.
 *
 *   host <unpacked FMU dir> <modelIdentifier> <guid> <script>
 *
 * Script lines (one command each; '#' starts a comment):
 *   instantiate [loggingOn 0|1]   setup <t0>   enter   exit   terminate   free   reset
 *   set_real <vr> <v>   set_string <vr> <s>   set_bool <vr> <0|1>   get_real <vr>
 *   inputs <vr>...      outputs <vr>...      step <h> <input values...>   (prints a ROW line)
 *   getstate   setstate   freestate   serialize   set_int <vr> <v>   get_int <vr>
 *   roundtrip (serialize the state, deserialize it into a new one and set it)
 *   save_state <file> (serialize to a file)   load_state <file> (deserialize from a file and set it)
 *   repeat <n> <h> <input values...> (n steps, prints the last ROW and "TIMING <median ns per fmi2DoStep>")
 *   cycles <n> (n instantiate/free cycles with the script's last instantiate arguments; prints
 *              "TIMING_CYCLE <mean ns per instantiate + free>")
 *   rss (prints "RSS <resident set size in kB>", Linux)
 * Output: "STATUS <command> <fmi2Status>", "VALUE <vr> <v>", "ROW <status> <t> <outputs...>",
 * "LOG <status> <category> <message>". Exit status 0 when the script ran to its end.
 */
#if defined(_WIN32)
#define __USE_MINGW_ANSI_STDIO 1
#include <windows.h>
#else
#define _POSIX_C_SOURCE 200809L
#include <dlfcn.h>
#include <time.h>
#endif
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* strtok_r of POSIX (mingw-w64 may lack it) */
static char *tok_r(char *s, const char *delim, char **save) {
    char *p = s ? s : *save;
    if (!p) return NULL;
    p += strspn(p, delim);
    if (!*p) {
        *save = p;
        return NULL;
    }
    char *e = p + strcspn(p, delim);
    if (*e) *e++ = 0;
    *save = e;
    return p;
}
#define strtok_r tok_r

static double now_ns(void) {
#if defined(_WIN32)
    LARGE_INTEGER f, c;
    QueryPerformanceFrequency(&f);
    QueryPerformanceCounter(&c);
    return (double)c.QuadPart * 1e9 / (double)f.QuadPart;
#else
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e9 + ts.tv_nsec;
#endif
}

static int cmp_d(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

typedef void *fmi2Component;
typedef void *fmi2FMUstate;
typedef unsigned int fmi2ValueReference;
typedef int fmi2Status;
typedef void (*Logger)(void *, const char *, int, const char *, const char *, ...);
typedef struct {
    Logger logger;
    void *(*allocateMemory)(size_t, size_t);
    void (*freeMemory)(void *);
    void (*stepFinished)(void *, int);
    void *env;
} Callbacks;

static void logger(void *env, const char *name, int status, const char *cat, const char *fmt, ...) {
    (void)env;
    (void)name;
    char buf[8192];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(buf, sizeof buf, fmt, ap);
    va_end(ap);
    for (char *p = buf; *p; p++)
        if (*p == '\n') *p = ' ';
    printf("LOG %d %s %s\n", status, cat, buf);
}

#if defined(_WIN32)
static HMODULE lib;
static void *fn(const char *name) {
    void *f = (void *)GetProcAddress(lib, name);
#else
static void *lib;
static void *fn(const char *name) {
    void *f = dlsym(lib, name);
#endif
    if (!f) {
        fprintf(stderr, "missing %s\n", name);
        exit(3);
    }
    return f;
}

int main(int argc, char **argv) {
    if (argc != 5) {
        fprintf(stderr, "usage: host <fmu dir> <modelIdentifier> <guid> <script>\n");
        return 2;
    }
    char path[4096], uri[8400];
#if defined(_WIN32)
    snprintf(path, sizeof path, "%s/binaries/win64/%s.dll", argv[1], argv[2]);
    lib = LoadLibraryA(path);
    if (!lib) {
        fprintf(stderr, "LoadLibrary %s: error %lu\n", path, (unsigned long)GetLastError());
        return 3;
    }
#else
    snprintf(path, sizeof path, "%s/binaries/linux64/%s.so", argv[1], argv[2]);
    lib = dlopen(path, RTLD_NOW | RTLD_LOCAL);
    if (!lib) {
        fprintf(stderr, "dlopen: %s\n", dlerror());
        return 3;
    }
#endif
    {   /* file URI of <dir>/resources: percent-escapes; a Windows drive letter (C:\x -> file:///C:/x) */
        char res[4200];
        snprintf(res, sizeof res, "%s/resources", argv[1]);
        size_t k = (size_t)snprintf(uri, sizeof uri, "file://%s", res[0] == '/' ? "" : "/");
        for (const unsigned char *p = (const unsigned char *)res; *p && k + 4 < sizeof uri; p++) {
            unsigned ch = *p == '\\' ? '/' : *p;
            if ((ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') || (ch >= '0' && ch <= '9') || strchr("/-._~:", (int)ch))
                uri[k++] = (char)ch;
            else
                k += (size_t)snprintf(uri + k, sizeof uri - k, "%%%02X", ch);
        }
        uri[k] = 0;
    }
    fmi2Component (*inst)(const char *, int, const char *, const char *, const Callbacks *, int, int) =
        (fmi2Component (*)(const char *, int, const char *, const char *, const Callbacks *, int, int))fn("fmi2Instantiate");
    fmi2Status (*setup)(fmi2Component, int, double, double, int, double) =
        (fmi2Status (*)(fmi2Component, int, double, double, int, double))fn("fmi2SetupExperiment");
    fmi2Status (*enter)(fmi2Component) = (fmi2Status (*)(fmi2Component))fn("fmi2EnterInitializationMode");
    fmi2Status (*exitm)(fmi2Component) = (fmi2Status (*)(fmi2Component))fn("fmi2ExitInitializationMode");
    fmi2Status (*term)(fmi2Component) = (fmi2Status (*)(fmi2Component))fn("fmi2Terminate");
    fmi2Status (*reset)(fmi2Component) = (fmi2Status (*)(fmi2Component))fn("fmi2Reset");
    void (*freei)(fmi2Component) = (void (*)(fmi2Component))fn("fmi2FreeInstance");
    fmi2Status (*setReal)(fmi2Component, const fmi2ValueReference *, size_t, const double *) =
        (fmi2Status (*)(fmi2Component, const fmi2ValueReference *, size_t, const double *))fn("fmi2SetReal");
    fmi2Status (*getReal)(fmi2Component, const fmi2ValueReference *, size_t, double *) =
        (fmi2Status (*)(fmi2Component, const fmi2ValueReference *, size_t, double *))fn("fmi2GetReal");
    fmi2Status (*setString)(fmi2Component, const fmi2ValueReference *, size_t, const char *const *) =
        (fmi2Status (*)(fmi2Component, const fmi2ValueReference *, size_t, const char *const *))fn("fmi2SetString");
    fmi2Status (*setBool)(fmi2Component, const fmi2ValueReference *, size_t, const int *) =
        (fmi2Status (*)(fmi2Component, const fmi2ValueReference *, size_t, const int *))fn("fmi2SetBoolean");
    fmi2Status (*doStep)(fmi2Component, double, double, int) =
        (fmi2Status (*)(fmi2Component, double, double, int))fn("fmi2DoStep");
    fmi2Status (*getState)(fmi2Component, fmi2FMUstate *) = (fmi2Status (*)(fmi2Component, fmi2FMUstate *))fn("fmi2GetFMUstate");
    fmi2Status (*setState)(fmi2Component, fmi2FMUstate) = (fmi2Status (*)(fmi2Component, fmi2FMUstate))fn("fmi2SetFMUstate");
    fmi2Status (*freeState)(fmi2Component, fmi2FMUstate *) = (fmi2Status (*)(fmi2Component, fmi2FMUstate *))fn("fmi2FreeFMUstate");
    fmi2Status (*serialize)(fmi2Component, fmi2FMUstate, char *, size_t) =
        (fmi2Status (*)(fmi2Component, fmi2FMUstate, char *, size_t))fn("fmi2SerializeFMUstate");
    fmi2Status (*serSize)(fmi2Component, fmi2FMUstate, size_t *) =
        (fmi2Status (*)(fmi2Component, fmi2FMUstate, size_t *))fn("fmi2SerializedFMUstateSize");
    fmi2Status (*deserialize)(fmi2Component, const char *, size_t, fmi2FMUstate *) =
        (fmi2Status (*)(fmi2Component, const char *, size_t, fmi2FMUstate *))fn("fmi2DeSerializeFMUstate");
    fmi2Status (*setInt)(fmi2Component, const fmi2ValueReference *, size_t, const int *) =
        (fmi2Status (*)(fmi2Component, const fmi2ValueReference *, size_t, const int *))fn("fmi2SetInteger");
    fmi2Status (*getInt)(fmi2Component, const fmi2ValueReference *, size_t, int *) =
        (fmi2Status (*)(fmi2Component, const fmi2ValueReference *, size_t, int *))fn("fmi2GetInteger");
    int last_log = 0;

    static Callbacks cb = {logger, calloc, free, NULL, NULL};
    FILE *f = fopen(argv[4], "r");
    if (!f) {
        fprintf(stderr, "cannot open %s\n", argv[4]);
        return 2;
    }
    fmi2Component c = NULL;
    fmi2FMUstate state = NULL;
    fmi2ValueReference in[64], out[256];
    size_t nin = 0, nout = 0;
    double t = 0.0;
    char line[65536];
    while (fgets(line, sizeof line, f)) {
        char *save = NULL;
        char *cmd = strtok_r(line, " \t\r\n", &save);
        if (!cmd || cmd[0] == '#') continue;
        char *a1 = strtok_r(NULL, " \t\r\n", &save);
        char *a2 = strtok_r(NULL, "\r\n", &save);
        fmi2Status st = 0;
        if (!strcmp(cmd, "instantiate")) {
            last_log = a1 ? atoi(a1) : 0;
            c = inst("bearing", 1, argv[3], uri, &cb, 0, last_log);
            st = c ? 0 : 3;
        } else if (!strcmp(cmd, "cycles")) {
            int n = atoi(a1);
            double t1 = now_ns();
            for (int i = 0; i < n && st == 0; i++) {
                fmi2Component c2 = inst("bearing", 1, argv[3], uri, &cb, 0, last_log);
                if (!c2) st = 3;
                else freei(c2);
            }
            printf("TIMING_CYCLE %.1f\n", n > 0 ? (now_ns() - t1) / n : 0.0);
        } else if (!strcmp(cmd, "rss")) {
            long kb = -1;
#if !defined(_WIN32)
            FILE *sf = fopen("/proc/self/status", "r");
            char l2[256];
            while (sf && fgets(l2, sizeof l2, sf))
                if (!strncmp(l2, "VmRSS:", 6)) kb = atol(l2 + 6);
            if (sf) fclose(sf);
#endif
            printf("RSS %ld\n", kb);
            fflush(stdout);
            continue;
        } else if (!strcmp(cmd, "set_int")) {
            fmi2ValueReference vr = (fmi2ValueReference)atoi(a1);
            int v = atoi(a2);
            st = setInt(c, &vr, 1, &v);
        } else if (!strcmp(cmd, "get_int")) {
            fmi2ValueReference vr = (fmi2ValueReference)atoi(a1);
            int v = -12345;
            st = getInt(c, &vr, 1, &v);
            printf("VALUE %u %d\n", vr, v);
        } else if (!strcmp(cmd, "roundtrip") || !strcmp(cmd, "save_state")) {
            size_t n = 0;
            st = serSize(c, state, &n);
            char *buf = st == 0 ? (char *)malloc(n) : NULL;
            if (buf) st = serialize(c, state, buf, n);
            if (buf && st == 0 && cmd[0] == 'r') {
                fmi2FMUstate s2 = NULL;
                st = deserialize(c, buf, n, &s2);
                if (st == 0) st = setState(c, s2);
                if (s2) freeState(c, &s2);
            } else if (buf && st == 0) {
                FILE *o = fopen(a1, "wb");
                if (!o || fwrite(buf, 1, n, o) != n) st = 3;
                if (o) fclose(o);
            }
            free(buf);
        } else if (!strcmp(cmd, "load_state")) {
            FILE *in = fopen(a1, "rb");
            char *buf = NULL;
            long n = 0;
            if (in && fseek(in, 0, SEEK_END) == 0 && (n = ftell(in)) >= 0) {
                rewind(in);
                buf = (char *)malloc((size_t)n + 1);
                if (buf && fread(buf, 1, (size_t)n, in) != (size_t)n) n = -1;
            }
            if (in) fclose(in);
            fmi2FMUstate s2 = NULL;
            st = (buf && n >= 0) ? deserialize(c, buf, (size_t)n, &s2) : 3;
            if (st == 0) st = setState(c, s2);
            if (s2) freeState(c, &s2);
            free(buf);
        } else if (!strcmp(cmd, "repeat")) {
            int n = atoi(a1);
            char *s2 = NULL;
            char *hs = strtok_r(a2, " \t", &s2);
            double h = hs ? atof(hs) : 1e-3, u[64], y[256];
            size_t nu = 0;
            for (char *tok = strtok_r(NULL, " \t", &s2); tok && nu < nin; tok = strtok_r(NULL, " \t", &s2))
                u[nu++] = atof(tok);
            double *dt = (double *)malloc(sizeof(double) * (size_t)(n > 0 ? n : 1));
            fmi2Status worst = 0;
            for (int i = 0; i < n; i++) {
                if (nu) setReal(c, in, nu, u);
                double t1 = now_ns();
                fmi2Status s1 = doStep(c, t, h, 1);
                dt[i] = now_ns() - t1;
                if (s1 > worst) worst = s1;
                if (s1 <= 1) t += h;
                getReal(c, out, nout, y);
            }
            qsort(dt, (size_t)n, sizeof(double), cmp_d);
            printf("TIMING %.1f\n", n > 0 ? dt[n / 2] : 0.0);
            printf("ROW %d 0 %.9f", worst, t);
            for (size_t k = 0; k < nout; k++) printf(" %.17g", y[k]);
            printf("\n");
            free(dt);
            fflush(stdout);
            continue;
        } else if (!strcmp(cmd, "setup")) {
            t = a1 ? atof(a1) : 0.0;
            st = setup(c, 0, 0.0, t, 0, 0.0);
        } else if (!strcmp(cmd, "enter")) {
            st = enter(c);
        } else if (!strcmp(cmd, "exit")) {
            st = exitm(c);
        } else if (!strcmp(cmd, "terminate")) {
            st = term(c);
        } else if (!strcmp(cmd, "reset")) {
            st = reset(c);
        } else if (!strcmp(cmd, "free")) {
            freei(c);
            c = NULL;
        } else if (!strcmp(cmd, "set_real")) {
            fmi2ValueReference vr = (fmi2ValueReference)atoi(a1);
            double v = atof(a2);
            st = setReal(c, &vr, 1, &v);
        } else if (!strcmp(cmd, "set_string")) {
            fmi2ValueReference vr = (fmi2ValueReference)atoi(a1);
            const char *v = a2 ? a2 : "";
            st = setString(c, &vr, 1, &v);
        } else if (!strcmp(cmd, "set_bool")) {
            fmi2ValueReference vr = (fmi2ValueReference)atoi(a1);
            int v = atoi(a2);
            st = setBool(c, &vr, 1, &v);
        } else if (!strcmp(cmd, "get_real")) {
            fmi2ValueReference vr = (fmi2ValueReference)atoi(a1);
            double v = -12345.0;
            st = getReal(c, &vr, 1, &v);
            printf("VALUE %u %.17g\n", vr, v);
        } else if (!strcmp(cmd, "inputs") || !strcmp(cmd, "outputs")) {
            fmi2ValueReference *dst = cmd[0] == 'i' ? in : out;
            size_t cap = cmd[0] == 'i' ? 64 : 256, n = 0;
            if (a1) dst[n++] = (fmi2ValueReference)atoi(a1);
            char *s2 = NULL;
            for (char *tok = a2 ? strtok_r(a2, " \t", &s2) : NULL; tok && n < cap; tok = strtok_r(NULL, " \t", &s2))
                dst[n++] = (fmi2ValueReference)atoi(tok);
            if (cmd[0] == 'i') nin = n; else nout = n;
            continue;
        } else if (!strcmp(cmd, "step")) {
            double h = atof(a1), u[64], y[256];
            size_t n = 0;
            char *s2 = NULL;
            for (char *tok = a2 ? strtok_r(a2, " \t", &s2) : NULL; tok && n < nin; tok = strtok_r(NULL, " \t", &s2))
                u[n++] = atof(tok);
            fmi2Status s1 = n ? setReal(c, in, n, u) : 0;
            st = doStep(c, t, h, 0);
            if (s1 > st) st = s1;
            if (st <= 1) t += h;
            fmi2Status s3 = getReal(c, out, nout, y);
            printf("ROW %d %d %.9f", st, s3, t);
            for (size_t k = 0; k < nout; k++) printf(" %.17g", y[k]);
            printf("\n");
            fflush(stdout);
            continue;
        } else if (!strcmp(cmd, "getstate")) {
            st = getState(c, &state);
        } else if (!strcmp(cmd, "setstate")) {
            st = setState(c, state);
        } else if (!strcmp(cmd, "freestate")) {
            st = freeState(c, &state);
        } else if (!strcmp(cmd, "serialize")) {
            char buf[64];
            st = serialize(c, state, buf, sizeof buf);
        } else {
            fprintf(stderr, "unknown command %s\n", cmd);
            return 2;
        }
        printf("STATUS %s %d\n", cmd, st);
        fflush(stdout);
    }
    fclose(f);
    fflush(stdout);
    return 0;
}
