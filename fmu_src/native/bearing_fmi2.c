/* Native FMI 2.0 co-simulation layer of the bearing FMU.
 *
 * The model itself is Python (fmu_src/bearing_fmu.py, a pythonfmu Fmi2Slave, driven through
 * resources/bearing_fmi2_bridge.py). This library only moves FMI calls into that Python code:
 *
 *  - Python is found at run time, never linked: if the host process already runs an initialised
 *    interpreter (fmpy, libcosimpy, ...) it is used; otherwise the libpython recorded at build time in
 *    resources/python_env.json (override: BEARING_FMU_PYTHON_LIB, home: BEARING_FMU_PYTHONHOME) is
 *    dlopen()ed with RTLD_GLOBAL (extension modules such as numpy resolve the C API from it) and
 *    initialised. Every call into Python holds the GIL through PyGILState_Ensure/Release, so any host
 *    thread may call.
 *  - The C API is reached through function pointers resolved with dlsym/GetProcAddress; the library
 *    therefore has no undefined Python symbols and needs no Python headers to build.
 *  - No static object has a destructor, no atexit/unload hook is registered, and the interpreter is
 *    never finalised: not one the host owns (it is not ours), and not one we started either, because
 *    numba/llvmlite and numpy cannot be unloaded and re-initialised safely (Py_FinalizeEx is documented
 *    to leak or crash with such extension modules) and finalising at process exit would run Python
 *    teardown after the host's own libraries are half destroyed. At exit the operating system
 *    reclaims the interpreter's memory. Python objects never hold pointers into this library, so the
 *    host may unload it at any time after fmi2FreeInstance.
 *
 * Portable C99; POSIX (dlopen) and Windows (LoadLibrary) branches. Tested here on linux64 only.
 */
#if !defined(_WIN32) && !defined(_GNU_SOURCE)
#define _GNU_SOURCE
#endif
#include "fmi2_min.h"

#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <wchar.h>

#if defined(_WIN32)
#include <windows.h>
typedef HMODULE lib_t;
static SRWLOCK g_lock = SRWLOCK_INIT;
#define LOCK() AcquireSRWLockExclusive(&g_lock)
#define UNLOCK() ReleaseSRWLockExclusive(&g_lock)
#define PATH_SEP '\\'
#else
#include <dlfcn.h>
#include <pthread.h>
typedef void *lib_t;
static pthread_mutex_t g_lock = PTHREAD_MUTEX_INITIALIZER;
#define LOCK() pthread_mutex_lock(&g_lock)
#define UNLOCK() pthread_mutex_unlock(&g_lock)
#define PATH_SEP '/'
#endif

#define MODEL_MAGIC 0x42524731u /* "BRG1": marks a live component */
#define PY_FILE_INPUT 257       /* Py_file_input */

typedef struct PyObj PyObject; /* opaque */

/* The Python C API subset used here (all functions of the stable ABI). Plain pointers: no destructor. */
static struct {
    int state; /* 0 not tried, 1 ready, -1 failed (error[] says why) */
    char error[2048];
    int own;   /* 1: this library initialised the interpreter */
    int (*IsInitialized)(void);
    void (*InitializeEx)(int);
    void (*SetPythonHome)(const wchar_t *);
    wchar_t *(*DecodeLocale)(const char *, size_t *);
    void *(*SaveThread)(void);
    int (*GILEnsure)(void);
    void (*GILRelease)(int);
    PyObject *(*CompileString)(const char *, const char *, int);
    PyObject *(*ExecCodeModuleEx)(const char *, PyObject *, const char *);
    PyObject *(*GetModuleDict)(void);
    PyObject *(*DictGetItemString)(PyObject *, const char *);
    PyObject *(*GetAttrString)(PyObject *, const char *);
    PyObject *(*VaBuildValue)(const char *, va_list);
    PyObject *(*CallObject)(PyObject *, PyObject *);
    long (*LongAsLong)(PyObject *);
    char *(*BytesAsString)(PyObject *);
    intptr_t (*BytesSize)(PyObject *);
    void (*DecRef)(PyObject *);
    void (*IncRef)(PyObject *);
    PyObject *(*ErrOccurred)(void);
    void (*ErrPrint)(void);
    const char *(*GetVersion)(void);
} py;

typedef struct {
    unsigned magic;
    PyObject *obj; /* the bridge's Instance */
    fmi2CallbackLogger logger;
    fmi2ComponentEnvironment env;
    char *name;
} Comp;

/* ---------------------------------------------------------------------------------------------- */
/* small helpers                                                                                   */

static void copy_str(char *dst, size_t n, const char *src) {
    if (n == 0) return;
    size_t k = strlen(src);
    if (k >= n) k = n - 1;
    memcpy(dst, src, k);
    dst[k] = '\0';
}

static char *read_file(const char *path) {
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    size_t cap = 1 << 16, len = 0;
    char *buf = (char *)malloc(cap + 1);
    while (buf) {
        size_t r = fread(buf + len, 1, cap - len, f);
        len += r;
        if (len < cap) break;
        char *nb = (char *)realloc(buf, 2 * cap + 1);
        if (!nb) { free(buf); buf = NULL; break; }
        buf = nb;
        cap *= 2;
    }
    fclose(f);
    if (buf) buf[len] = '\0';
    return buf;
}

/* Value of a top-level string member "key" of a flat JSON object (UTF-8, escapes \" \\ \/ \n \t). */
static int json_string(const char *js, const char *key, char *out, size_t n) {
    char pat[128];
    snprintf(pat, sizeof pat, "\"%s\"", key);
    const char *p = js ? strstr(js, pat) : NULL;
    if (!p || n == 0) return 0;
    p += strlen(pat);
    while (*p == ' ' || *p == '\t' || *p == '\n' || *p == '\r') p++;
    if (*p++ != ':') return 0;
    while (*p == ' ' || *p == '\t' || *p == '\n' || *p == '\r') p++;
    if (*p++ != '"') return 0;
    size_t k = 0;
    while (*p && *p != '"' && k + 1 < n) {
        char ch = *p++;
        if (ch == '\\') {
            ch = *p++;
            if (ch == 'n') ch = '\n';
            else if (ch == 't') ch = '\t';
            else if (ch == '\0') break;
        }
        out[k++] = ch;
    }
    out[k] = '\0';
    return *p == '"';
}

/* fmuResourceLocation (file URI) -> local path; NULL/empty: <this library>/../../resources. */
static int resource_dir(const char *uri, char *out, size_t n) {
    if (uri && *uri) {
        const char *p = uri;
        if (strncmp(p, "file://localhost/", 17) == 0) p += 16;
        else if (strncmp(p, "file:///", 8) == 0) p += 7;
        else if (strncmp(p, "file:/", 6) == 0) p += 5;
        else if (strncmp(p, "file:", 5) == 0) return 0;
#if defined(_WIN32)
        if (p[0] == '/' && p[1] && p[2] == ':') p++; /* file:///C:/... */
#endif
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
        while (k > 1 && (out[k - 1] == '/' || out[k - 1] == '\\')) out[--k] = '\0';
        return k > 0;
    }
#if defined(_WIN32)
    HMODULE self = NULL;
    if (!GetModuleHandleExA(GET_MODULE_HANDLE_EX_FLAG_FROM_ADDRESS | GET_MODULE_HANDLE_EX_FLAG_UNCHANGED_REFCOUNT,
                            (LPCSTR)&resource_dir, &self))
        return 0;
    char so[4096];
    if (!GetModuleFileNameA(self, so, sizeof so)) return 0;
#else
    Dl_info info;
    if (!dladdr((void *)&resource_dir, &info) || !info.dli_fname) return 0;
    char so[4096];
    copy_str(so, sizeof so, info.dli_fname);
#endif
    for (int up = 0; up < 3; up++) { /* strip <file>, <platform>, binaries */
        char *s1 = strrchr(so, '/'), *s2 = strrchr(so, '\\');
        char *s = s1 > s2 ? s1 : s2;
        if (!s) return 0;
        *s = '\0';
    }
    snprintf(out, n, "%s%cresources", so, PATH_SEP);
    return 1;
}

static void *sym(lib_t lib, const char *name) {
#if defined(_WIN32)
    return (void *)GetProcAddress(lib, name);
#else
    return dlsym(lib, name);
#endif
}

/* ---------------------------------------------------------------------------------------------- */
/* Python start-up (once per loaded copy of this library)                                          */

static int resolve(lib_t lib) {
#define R(field, name)                                                                        \
    do {                                                                                      \
        *(void **)(&py.field) = sym(lib, name);                                               \
        if (!py.field) {                                                                      \
            snprintf(py.error, sizeof py.error, "libpython lacks the C API function %s", name); \
            return 0;                                                                         \
        }                                                                                     \
    } while (0)
    R(IsInitialized, "Py_IsInitialized");
    R(InitializeEx, "Py_InitializeEx");
    R(DecodeLocale, "Py_DecodeLocale");
    R(SaveThread, "PyEval_SaveThread");
    R(GILEnsure, "PyGILState_Ensure");
    R(GILRelease, "PyGILState_Release");
    R(CompileString, "Py_CompileString");
    R(ExecCodeModuleEx, "PyImport_ExecCodeModuleEx");
    R(GetModuleDict, "PyImport_GetModuleDict");
    R(DictGetItemString, "PyDict_GetItemString");
    R(GetAttrString, "PyObject_GetAttrString");
    R(VaBuildValue, "Py_VaBuildValue");
    R(CallObject, "PyObject_CallObject");
    R(LongAsLong, "PyLong_AsLong");
    R(BytesAsString, "PyBytes_AsString");
    R(BytesSize, "PyBytes_Size");
    R(DecRef, "Py_DecRef");
    R(IncRef, "Py_IncRef");
    R(ErrOccurred, "PyErr_Occurred");
    R(ErrPrint, "PyErr_Print");
    R(GetVersion, "Py_GetVersion");
#undef R
    *(void **)(&py.SetPythonHome) = sym(lib, "Py_SetPythonHome"); /* optional (removed in 3.13) */
    return 1;
}

#if defined(_WIN32)
static const char *base_name(const char *path) {
    const char *s1 = strrchr(path, '/'), *s2 = strrchr(path, '\\');
    const char *s = s1 > s2 ? s1 : s2;
    return s ? s + 1 : path;
}
#endif

static int py_start(const char *envjson) {
    char libpath[4096] = "", home[4096] = "", version[32] = "";
    const char *ov = getenv("BEARING_FMU_PYTHON_LIB");
    if (ov && *ov) copy_str(libpath, sizeof libpath, ov);
    else json_string(envjson, "libpython", libpath, sizeof libpath);
    ov = getenv("BEARING_FMU_PYTHONHOME");
    if (ov && *ov) copy_str(home, sizeof home, ov);
    else json_string(envjson, "python_home", home, sizeof home);
    json_string(envjson, "python_version", version, sizeof version);

    /* 1. an interpreter already running in the host process */
    lib_t lib = NULL;
#if defined(_WIN32)
    if (*libpath) lib = GetModuleHandleA(base_name(libpath));
#else
    lib = RTLD_DEFAULT;
#endif
    int (*isinit)(void) = lib ? (int (*)(void))sym(lib, "Py_IsInitialized") : NULL;
    if (!(isinit && isinit())) {
        /* 2. the Python the FMU was built for */
        if (!*libpath) {
            snprintf(py.error, sizeof py.error, "no Python library: resources/python_env.json names none and "
                                                "BEARING_FMU_PYTHON_LIB is not set");
            return 0;
        }
#if defined(_WIN32)
        lib = LoadLibraryA(libpath);
        if (!lib) {
            snprintf(py.error, sizeof py.error, "cannot load the Python library %s (error %lu); set "
                     "BEARING_FMU_PYTHON_LIB to the python3x.dll of a Python %s with numpy, scipy and numba",
                     libpath, (unsigned long)GetLastError(), version);
            return 0;
        }
#else
        lib = dlopen(libpath, RTLD_NOW | RTLD_GLOBAL);
        if (!lib) {
            snprintf(py.error, sizeof py.error, "cannot load the Python library: %s; set BEARING_FMU_PYTHON_LIB "
                     "to the libpython of a Python %s with numpy, scipy and numba", dlerror(), version);
            return 0;
        }
#endif
    }
    if (!resolve(lib)) return 0;
    const char *v = py.GetVersion();
    size_t lv = strlen(version);
    if (lv && !(strncmp(v, version, lv) == 0 && (v[lv] == '.' || v[lv] == ' ' || v[lv] == '\0'))) {
        snprintf(py.error, sizeof py.error, "the FMU was built for Python %s but the process runs Python %.20s "
                 "(rebuild the FMU with that Python, or point BEARING_FMU_PYTHON_LIB to a Python %s)", version, v,
                 version);
        return 0;
    }
    if (!py.IsInitialized()) {
        if (*home) {
            /* Python keeps this pointer: the buffer is deliberately never freed (one per process). */
            wchar_t *whome = py.DecodeLocale(home, NULL);
            if (py.SetPythonHome && whome) py.SetPythonHome(whome);
#if !defined(_WIN32)
            else if (!getenv("PYTHONHOME")) setenv("PYTHONHOME", home, 0);
#endif
        }
        py.InitializeEx(0); /* 0: leave the host's signal handlers alone */
        if (!py.IsInitialized()) {
            snprintf(py.error, sizeof py.error, "Python %s (home %s) failed to initialise", version, home);
            return 0;
        }
        py.own = 1;
        py.SaveThread(); /* release the GIL: every call below takes it with PyGILState_Ensure */
    }
    return 1;
}

/* ---------------------------------------------------------------------------------------------- */
/* calls into the bridge                                                                            */

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

/* The bridge's queued log records: "<status>\x1f<category>\x1f<message>\0" repeated. Copied out under the
 * GIL and emitted after releasing it (the master's logger may take locks of its own). */
static char *take_logs(PyObject *obj, size_t *len) {
    *len = 0;
    PyObject *f = py.GetAttrString(obj, "take_logs");
    if (!f) { py.ErrPrint(); return NULL; }
    PyObject *r = py.CallObject(f, NULL);
    py.DecRef(f);
    if (!r) { py.ErrPrint(); return NULL; }
    char *out = NULL;
    intptr_t n = py.BytesSize(r);
    char *s = n > 0 ? py.BytesAsString(r) : NULL;
    if (s && n > 0) {
        out = (char *)malloc((size_t)n + 1);
        if (out) { memcpy(out, s, (size_t)n); out[n] = '\0'; *len = (size_t)n; }
    }
    if (py.ErrOccurred()) py.ErrPrint();
    py.DecRef(r);
    return out;
}

static void emit_logs(Comp *c, char *buf, size_t len) {
    size_t i = 0;
    while (buf && i < len) {
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

static PyObject *call_method(PyObject *obj, const char *meth, const char *fmt, va_list ap) {
    PyObject *f = py.GetAttrString(obj, meth);
    if (!f) return NULL;
    PyObject *args = py.VaBuildValue(fmt, ap);
    if (!args) { py.DecRef(f); return NULL; }
    PyObject *r = py.CallObject(f, args);
    py.DecRef(args);
    py.DecRef(f);
    return r;
}

static PyObject *build_args(const char *fmt, ...) {
    va_list ap;
    va_start(ap, fmt);
    PyObject *r = py.VaBuildValue(fmt, ap);
    va_end(ap);
    return r;
}

/* Calls Instance.<meth>(*args) and returns its integer fmi2Status; fmt must build a tuple, e.g. "(dd)". */
static fmi2Status invoke(fmi2Component comp, const char *meth, const char *fmt, ...) {
    Comp *c = (Comp *)comp;
    if (!c || c->magic != MODEL_MAGIC) return fmi2Error; /* not one of ours (or freed): nobody to log to */
    int g = py.GILEnsure();
    va_list ap;
    va_start(ap, fmt);
    PyObject *r = call_method(c->obj, meth, fmt, ap);
    va_end(ap);
    long st = fmi2Error;
    int internal = 0;
    if (r) {
        st = py.LongAsLong(r);
        py.DecRef(r);
        if (py.ErrOccurred()) { py.ErrPrint(); st = fmi2Error; internal = 1; }
    } else {
        py.ErrPrint(); /* the bridge catches everything; this is a defect: traceback to stderr */
        internal = 1;
    }
    size_t n;
    char *logs = take_logs(c->obj, &n);
    py.GILRelease(g);
    emit_logs(c, logs, n);
    if (internal) {
        char msg[256];
        snprintf(msg, sizeof msg, "internal error in %s of the FMU's Python layer (traceback on stderr)", meth);
        log_to(c->logger, c->env, c->name, fmi2Error, "logError", msg);
    }
    if (st < fmi2OK || st > fmi2Fatal) st = fmi2Error;
    return (fmi2Status)st;
}

/* ---------------------------------------------------------------------------------------------- */
/* FMI 2.0 API                                                                                      */

FMI2_EXPORT const char *fmi2GetTypesPlatform(void) { return "default"; }
FMI2_EXPORT const char *fmi2GetVersion(void) { return "2.0"; }

FMI2_EXPORT fmi2Component fmi2Instantiate(fmi2String instanceName, fmi2Type fmuType, fmi2String fmuGUID,
                                          fmi2String fmuResourceLocation, const fmi2CallbackFunctions *functions,
                                          fmi2Boolean visible, fmi2Boolean loggingOn) {
    fmi2CallbackLogger logger = functions ? functions->logger : NULL;
    fmi2ComponentEnvironment env = functions ? functions->componentEnvironment : NULL;
    char msg[4096 + 512];
    if (fmuType != fmi2CoSimulation) {
        log_to(logger, env, instanceName, fmi2Error, "logError", "this FMU supports co-simulation only");
        return NULL;
    }
    char res[4096];
    if (!resource_dir(fmuResourceLocation, res, sizeof res)) {
        snprintf(msg, sizeof msg, "cannot use fmuResourceLocation '%s' (a file: URI is required)",
                 fmuResourceLocation ? fmuResourceLocation : "(null)");
        log_to(logger, env, instanceName, fmi2Error, "logError", msg);
        return NULL;
    }
    char path[4096 + 64];
    snprintf(path, sizeof path, "%s%cpython_env.json", res, PATH_SEP);
    char *envjson = read_file(path);
    if (!envjson) {
        snprintf(msg, sizeof msg, "cannot read %s", path);
        log_to(logger, env, instanceName, fmi2Error, "logError", msg);
        return NULL;
    }
    LOCK();
    if (py.state == 0) py.state = py_start(envjson) ? 1 : -1;
    UNLOCK();
    if (py.state != 1) {
        snprintf(msg, sizeof msg, "cannot start Python: %s", py.error);
        log_to(logger, env, instanceName, fmi2Error, "logError", msg);
        free(envjson);
        return NULL;
    }
    char modname[256] = "";
    json_string(envjson, "bridge_module", modname, sizeof modname);
    free(envjson);
    if (!*modname) {
        log_to(logger, env, instanceName, fmi2Error, "logError", "resources/python_env.json lacks bridge_module");
        return NULL;
    }
    Comp *c = (Comp *)calloc(1, sizeof(Comp));
    char *name = (char *)malloc(strlen(instanceName ? instanceName : "") + 1);
    if (!c || !name) {
        free(c);
        free(name);
        log_to(logger, env, instanceName, fmi2Error, "logError", "out of memory");
        return NULL;
    }
    strcpy(name, instanceName ? instanceName : "");
    c->logger = logger;
    c->env = env;
    c->name = name;

    int g = py.GILEnsure();
    PyObject *mod = py.DictGetItemString(py.GetModuleDict(), modname); /* borrowed */
    if (mod) {
        py.IncRef(mod);
    } else {
        snprintf(path, sizeof path, "%s%cbearing_fmi2_bridge.py", res, PATH_SEP);
        char *src = read_file(path);
        PyObject *code = src ? py.CompileString(src, path, PY_FILE_INPUT) : NULL;
        free(src);
        mod = code ? py.ExecCodeModuleEx(modname, code, path) : NULL;
        if (code) py.DecRef(code);
    }
    PyObject *obj = NULL;
    if (mod) {
        PyObject *f = py.GetAttrString(mod, "instantiate");
        if (f) {
            PyObject *args = build_args("(sssiii)", res, name, fmuGUID ? fmuGUID : "", (int)visible, (int)loggingOn,
                                      py.own);
            obj = args ? py.CallObject(f, args) : NULL;
            if (args) py.DecRef(args);
            py.DecRef(f);
        }
        py.DecRef(mod);
    }
    if (!obj) py.ErrPrint();
    size_t n = 0;
    char *logs = obj ? take_logs(obj, &n) : NULL;
    long ok = 0;
    if (obj) {
        PyObject *flag = py.GetAttrString(obj, "ok");
        if (flag) { ok = py.LongAsLong(flag); py.DecRef(flag); }
        if (py.ErrOccurred()) { py.ErrPrint(); ok = 0; }
        if (!ok) { py.DecRef(obj); obj = NULL; }
    }
    py.GILRelease(g);
    emit_logs(c, logs, n);
    if (!obj) {
        if (!ok && !n)
            log_to(logger, env, name, fmi2Error, "logError",
                   "the FMU's Python layer failed to load (traceback on stderr)");
        free(name);
        free(c);
        return NULL;
    }
    c->obj = obj;
    c->magic = MODEL_MAGIC;
    return (fmi2Component)c;
}

FMI2_EXPORT void fmi2FreeInstance(fmi2Component comp) {
    Comp *c = (Comp *)comp;
    if (!c || c->magic != MODEL_MAGIC) return;
    invoke(c, "free", "()");
    int g = py.GILEnsure();
    py.DecRef(c->obj);
    py.GILRelease(g);
    c->magic = 0;
    c->obj = NULL;
    free(c->name);
    free(c);
}

FMI2_EXPORT fmi2Status fmi2SetDebugLogging(fmi2Component c, fmi2Boolean on, size_t n, const fmi2String cats[]) {
    return invoke(c, "set_debug_logging", "(iKK)", (int)on, (unsigned long long)n,
                  (unsigned long long)(uintptr_t)cats);
}

FMI2_EXPORT fmi2Status fmi2SetupExperiment(fmi2Component c, fmi2Boolean tolDefined, fmi2Real tol, fmi2Real start,
                                           fmi2Boolean stopDefined, fmi2Real stop) {
    return invoke(c, "setup_experiment", "(idddi)", (int)tolDefined, tol, start, stop, (int)stopDefined);
}

FMI2_EXPORT fmi2Status fmi2EnterInitializationMode(fmi2Component c) { return invoke(c, "enter_initialization_mode", "()"); }
FMI2_EXPORT fmi2Status fmi2ExitInitializationMode(fmi2Component c) { return invoke(c, "exit_initialization_mode", "()"); }
FMI2_EXPORT fmi2Status fmi2Terminate(fmi2Component c) { return invoke(c, "terminate", "()"); }
FMI2_EXPORT fmi2Status fmi2Reset(fmi2Component c) { return invoke(c, "reset", "()"); }

#define ADDR(p) ((unsigned long long)(uintptr_t)(p))

FMI2_EXPORT fmi2Status fmi2GetReal(fmi2Component c, const fmi2ValueReference vr[], size_t n, fmi2Real v[]) {
    return invoke(c, "get_real", "(KKK)", ADDR(vr), (unsigned long long)n, ADDR(v));
}
FMI2_EXPORT fmi2Status fmi2GetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t n, fmi2Integer v[]) {
    return invoke(c, "get_integer", "(KKK)", ADDR(vr), (unsigned long long)n, ADDR(v));
}
FMI2_EXPORT fmi2Status fmi2GetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t n, fmi2Boolean v[]) {
    return invoke(c, "get_boolean", "(KKK)", ADDR(vr), (unsigned long long)n, ADDR(v));
}
FMI2_EXPORT fmi2Status fmi2GetString(fmi2Component c, const fmi2ValueReference vr[], size_t n, fmi2String v[]) {
    return invoke(c, "get_string", "(KKK)", ADDR(vr), (unsigned long long)n, ADDR(v));
}
FMI2_EXPORT fmi2Status fmi2SetReal(fmi2Component c, const fmi2ValueReference vr[], size_t n, const fmi2Real v[]) {
    return invoke(c, "set_real", "(KKK)", ADDR(vr), (unsigned long long)n, ADDR(v));
}
FMI2_EXPORT fmi2Status fmi2SetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t n,
                                      const fmi2Integer v[]) {
    return invoke(c, "set_integer", "(KKK)", ADDR(vr), (unsigned long long)n, ADDR(v));
}
FMI2_EXPORT fmi2Status fmi2SetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t n,
                                      const fmi2Boolean v[]) {
    return invoke(c, "set_boolean", "(KKK)", ADDR(vr), (unsigned long long)n, ADDR(v));
}
FMI2_EXPORT fmi2Status fmi2SetString(fmi2Component c, const fmi2ValueReference vr[], size_t n,
                                     const fmi2String v[]) {
    return invoke(c, "set_string", "(KKK)", ADDR(vr), (unsigned long long)n, ADDR(v));
}

FMI2_EXPORT fmi2Status fmi2GetFMUstate(fmi2Component c, fmi2FMUstate *s) {
    return invoke(c, "get_fmu_state", "(K)", ADDR(s));
}
FMI2_EXPORT fmi2Status fmi2SetFMUstate(fmi2Component c, fmi2FMUstate s) {
    return invoke(c, "set_fmu_state", "(K)", ADDR(s));
}
FMI2_EXPORT fmi2Status fmi2FreeFMUstate(fmi2Component c, fmi2FMUstate *s) {
    return invoke(c, "free_fmu_state", "(K)", ADDR(s));
}
FMI2_EXPORT fmi2Status fmi2SerializedFMUstateSize(fmi2Component c, fmi2FMUstate s, size_t *size) {
    (void)s;
    (void)size;
    return invoke(c, "unsupported", "(s)", "fmi2SerializedFMUstateSize");
}
FMI2_EXPORT fmi2Status fmi2SerializeFMUstate(fmi2Component c, fmi2FMUstate s, fmi2Byte b[], size_t size) {
    (void)s;
    (void)b;
    (void)size;
    return invoke(c, "unsupported", "(s)", "fmi2SerializeFMUstate");
}
FMI2_EXPORT fmi2Status fmi2DeSerializeFMUstate(fmi2Component c, const fmi2Byte b[], size_t size, fmi2FMUstate *s) {
    (void)b;
    (void)size;
    (void)s;
    return invoke(c, "unsupported", "(s)", "fmi2DeSerializeFMUstate");
}
FMI2_EXPORT fmi2Status fmi2GetDirectionalDerivative(fmi2Component c, const fmi2ValueReference u[], size_t nu,
                                                    const fmi2ValueReference z[], size_t nz, const fmi2Real dv[],
                                                    fmi2Real df[]) {
    (void)u; (void)nu; (void)z; (void)nz; (void)dv; (void)df;
    return invoke(c, "unsupported", "(s)", "fmi2GetDirectionalDerivative");
}

/* co-simulation */
FMI2_EXPORT fmi2Status fmi2SetRealInputDerivatives(fmi2Component c, const fmi2ValueReference vr[], size_t n,
                                                   const fmi2Integer order[], const fmi2Real v[]) {
    (void)vr; (void)n; (void)order; (void)v;
    return invoke(c, "unsupported", "(s)", "fmi2SetRealInputDerivatives");
}
FMI2_EXPORT fmi2Status fmi2GetRealOutputDerivatives(fmi2Component c, const fmi2ValueReference vr[], size_t n,
                                                    const fmi2Integer order[], fmi2Real v[]) {
    (void)vr; (void)n; (void)order; (void)v;
    return invoke(c, "unsupported", "(s)", "fmi2GetRealOutputDerivatives");
}
FMI2_EXPORT fmi2Status fmi2DoStep(fmi2Component c, fmi2Real t, fmi2Real h, fmi2Boolean noSetFMUStatePriorToCurrentPoint) {
    return invoke(c, "do_step", "(ddi)", t, h, (int)noSetFMUStatePriorToCurrentPoint);
}
FMI2_EXPORT fmi2Status fmi2CancelStep(fmi2Component c) { return invoke(c, "unsupported", "(s)", "fmi2CancelStep"); }
FMI2_EXPORT fmi2Status fmi2GetStatus(fmi2Component c, const fmi2StatusKind s, fmi2Status *v) {
    return invoke(c, "get_status", "(iKs)", (int)s, ADDR(v), "status");
}
FMI2_EXPORT fmi2Status fmi2GetRealStatus(fmi2Component c, const fmi2StatusKind s, fmi2Real *v) {
    return invoke(c, "get_status", "(iKs)", (int)s, ADDR(v), "real");
}
FMI2_EXPORT fmi2Status fmi2GetIntegerStatus(fmi2Component c, const fmi2StatusKind s, fmi2Integer *v) {
    return invoke(c, "get_status", "(iKs)", (int)s, ADDR(v), "integer");
}
FMI2_EXPORT fmi2Status fmi2GetBooleanStatus(fmi2Component c, const fmi2StatusKind s, fmi2Boolean *v) {
    return invoke(c, "get_status", "(iKs)", (int)s, ADDR(v), "boolean");
}
FMI2_EXPORT fmi2Status fmi2GetStringStatus(fmi2Component c, const fmi2StatusKind s, fmi2String *v) {
    return invoke(c, "get_status", "(iKs)", (int)s, ADDR(v), "string");
}
