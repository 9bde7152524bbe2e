/* The shared FMI 2.0 co-simulation layer (fmi2_common.h): every fmi2* function, the state machine of FMI 2.0
 * section 4.3.1 (a call in a state that does not allow it returns fmi2Error with the reason logged), FMU states and
 * their serialisation (a versioned little-endian record checked before use), the resource location (file URIs on
 * Linux and Windows, percent-escapes) and the helpers the models share. No globals. C99, libc and libm. */
#if defined(_WIN32) && !defined(__USE_MINGW_ANSI_STDIO)
#define __USE_MINGW_ANSI_STDIO 1 /* C99 printf (%g of nan and inf, %zu) with mingw-w64 */
#endif
#include "fmi2_common.h"

#include <ctype.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define INSTANCE_MAGIC 0x42524D31u /* marks a live instance */
#define STATE_MAGIC 0x42524D53u    /* marks an FMU state of this layer */
#define SER_MAGIC "BRGSTATE"
#define SER_VERSION 1u
#define SER_HEADER 96u

static const char *CATEGORY[] = {"logInfo", "logWarning", "logDiscard", "logError", "logError", "logInfo"};
static const char *MODE_NAME[] = {"instantiated", "initialization", "step", "terminated", "failed"};

/* ---- byte helpers ------------------------------------------------------------------------------------------ */
void le_put_u32(unsigned char *p, unsigned v) {
    for (int k = 0; k < 4; k++) p[k] = (unsigned char)(v >> (8 * k));
}
unsigned le_get_u32(const unsigned char *p) {
    return (unsigned)p[0] | ((unsigned)p[1] << 8) | ((unsigned)p[2] << 16) | ((unsigned)p[3] << 24);
}
void le_put_f64(unsigned char *p, double v) {
    unsigned long long u;
    memcpy(&u, &v, 8);
    for (int k = 0; k < 8; k++) p[k] = (unsigned char)(u >> (8 * k));
}
double le_get_f64(const unsigned char *p) {
    unsigned long long u = 0;
    for (int k = 0; k < 8; k++) u |= (unsigned long long)p[k] << (8 * k);
    double v;
    memcpy(&v, &u, 8);
    return v;
}

unsigned crc32_ieee(const unsigned char *p, size_t n) {
    unsigned table[256]; /* on the stack: no globals */
    for (unsigned i = 0; i < 256; i++) {
        unsigned c = i;
        for (int k = 0; k < 8; k++) c = (c & 1u) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
        table[i] = c;
    }
    unsigned crc = 0xFFFFFFFFu;
    for (size_t i = 0; i < n; i++) crc = table[(crc ^ p[i]) & 0xFFu] ^ (crc >> 8);
    return crc ^ 0xFFFFFFFFu;
}

static int hexval(int ch) {
    if (ch >= '0' && ch <= '9') return ch - '0';
    if (ch >= 'a' && ch <= 'f') return ch - 'a' + 10;
    if (ch >= 'A' && ch <= 'F') return ch - 'A' + 10;
    return -1;
}

int uri_to_path(const char *uri, char *out, size_t n) {
    if (!uri || !out || n < 2) return -1;
    const char *p = uri;
    char tmp[4096];
    size_t k = 0;
    if (!strncmp(p, "file:", 5) || !strncmp(p, "FILE:", 5)) {
        p += 5;
        if (p[0] == '/' && p[1] == '/') { /* authority */
            p += 2;
            const char *slash = strchr(p, '/');
            size_t alen = slash ? (size_t)(slash - p) : strlen(p);
            if (alen > 0 && !(alen == 9 && !strncmp(p, "localhost", 9))) { /* a host: a UNC path */
                if (alen + 2 >= sizeof tmp) return -1;
                tmp[k++] = '/';
                tmp[k++] = '/';
                memcpy(tmp + k, p, alen);
                k += alen;
            }
            p += alen;
        }
    }
    for (; *p; p++) {
        if (k + 1 >= sizeof tmp) return -1;
        if (*p == '%' && hexval(p[1]) >= 0 && hexval(p[2]) >= 0) {
            tmp[k++] = (char)(hexval(p[1]) * 16 + hexval(p[2]));
            p += 2;
        } else {
            tmp[k++] = *p;
        }
    }
    tmp[k] = 0;
    const char *s = tmp;
    /* /C:/dir -> C:/dir (a Windows drive letter after the URI's root slash) */
    if (s[0] == '/' && isalpha((unsigned char)s[1]) && (s[2] == ':' || s[2] == '|') && (s[3] == '/' || !s[3])) s++;
    size_t len = strlen(s);
    if (len + 1 > n || len == 0) return -1;
    memcpy(out, s, len + 1);
    if (out[1] == '|') out[1] = ':';
    while (len > 1 && (out[len - 1] == '/' || out[len - 1] == '\\')) out[--len] = 0; /* no trailing separator */
    return 0;
}

void py_repr_double(double v, char *buf, size_t n) {
    if (isnan(v)) {
        snprintf(buf, n, "nan");
        return;
    }
    if (isinf(v)) {
        snprintf(buf, n, v > 0 ? "inf" : "-inf");
        return;
    }
    char e[40];
    int prec;
    for (prec = 1; prec <= 17; prec++) { /* the shortest digits that read back to v (Python's repr) */
        snprintf(e, sizeof e, "%.*e", prec - 1, v);
        if (strtod(e, NULL) == v) break;
    }
    /* e: [-]d[.ddd]e[+-]XX -> digits and decimal exponent */
    char digits[24];
    int nd = 0, neg = e[0] == '-';
    const char *q = e + neg;
    for (; *q && *q != 'e'; q++)
        if (isdigit((unsigned char)*q)) digits[nd++] = *q;
    int exp10 = atoi(q + 1);
    while (nd > 1 && digits[nd - 1] == '0') nd--;
    digits[nd] = 0;
    char out[64];
    size_t k = 0;
    if (neg) out[k++] = '-';
    if (exp10 >= -5 + 1 && exp10 < 16) { /* Python: fixed notation for 1e-4 <= |v| < 1e16 */
        if (exp10 < 0) {
            out[k++] = '0';
            out[k++] = '.';
            for (int i = 0; i < -exp10 - 1; i++) out[k++] = '0';
            for (int i = 0; i < nd; i++) out[k++] = digits[i];
        } else {
            for (int i = 0; i <= exp10; i++) out[k++] = i < nd ? digits[i] : '0';
            out[k++] = '.';
            if (nd > exp10 + 1)
                for (int i = exp10 + 1; i < nd; i++) out[k++] = digits[i];
            else
                out[k++] = '0';
        }
        out[k] = 0;
    } else {
        out[k++] = digits[0];
        if (nd > 1) {
            out[k++] = '.';
            for (int i = 1; i < nd; i++) out[k++] = digits[i];
        }
        out[k] = 0;
        snprintf(out + k, sizeof out - k, "e%c%02d", exp10 < 0 ? '-' : '+', exp10 < 0 ? -exp10 : exp10);
    }
    snprintf(buf, n, "%s", out);
}

void py_repr_string(const char *s, char *buf, size_t n) {
    if (n < 3) {
        if (n) buf[0] = 0;
        return;
    }
    char quote = (strchr(s, '\'') && !strchr(s, '"')) ? '"' : '\'';
    size_t k = 0;
    buf[k++] = quote;
    for (const unsigned char *p = (const unsigned char *)s; *p && k + 6 < n; p++) {
        if (*p == '\\' || *p == (unsigned char)quote) {
            buf[k++] = '\\';
            buf[k++] = (char)*p;
        } else if (*p == '\n') {
            buf[k++] = '\\';
            buf[k++] = 'n';
        } else if (*p == '\t') {
            buf[k++] = '\\';
            buf[k++] = 't';
        } else if (*p == '\r') {
            buf[k++] = '\\';
            buf[k++] = 'r';
        } else if (*p < 0x20 || *p == 0x7f) {
            k += (size_t)snprintf(buf + k, n - k, "\\x%02x", *p);
        } else {
            buf[k++] = (char)*p;
        }
    }
    buf[k++] = quote;
    buf[k] = 0;
}

/* ---- logging ------------------------------------------------------------------------------------------------ */
void fmu_log(Instance *c, int status, const char *fmt, ...) {
    if (!c || !c->logger) return;
    if (status == fmi2OK && !c->logging_on) return;
    char msg[8192];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    /* the message is the format (masters such as fmpy read no variadic arguments); a '%' is doubled so that a
       master that formats it prints it as it is */
    char fmtd[2 * sizeof msg];
    size_t k = 0;
    for (const char *p = msg; *p && k + 2 < sizeof fmtd; p++) {
        if (*p == '%') fmtd[k++] = '%';
        fmtd[k++] = *p;
    }
    fmtd[k] = 0;
    c->logger(c->env, c->name ? c->name : "", (fmi2Status)status, CATEGORY[status < 0 || status > 5 ? 3 : status],
              fmtd);
}

static void free_all_states(Instance *c); /* FMU states, below */

static Instance *valid(fmi2Component comp) {
    Instance *c = (Instance *)comp;
    return (c && c->magic == INSTANCE_MAGIC) ? c : NULL;
}

/* the call is allowed in the modes of mask (1 << MODE_*), else fmi2Error with the reason */
static int allowed(Instance *c, const char *fn, unsigned mask) {
    if (mask & (1u << c->mode)) return 1;
    if (c->mode == MODE_FAILED)
        fmu_log(c, fmi2Error, "%s: not allowed: the initialisation failed (%s)", fn, c->failure);
    else
        fmu_log(c, fmi2Error, "%s: not allowed in %s mode (FMI 2.0 section 4.3.1)", fn, MODE_NAME[c->mode]);
    return 0;
}
#define M(x) (1u << (x))
#define CHECK(fn, mask)                         \
    Instance *c = valid(comp);                  \
    if (!c) return fmi2Error;                   \
    if (!allowed(c, fn, mask)) return fmi2Error;

/* ---- instance ------------------------------------------------------------------------------------------------ */
FMI2_EXPORT const char *fmi2GetTypesPlatform(void) { return "default"; }
FMI2_EXPORT const char *fmi2GetVersion(void) { return "2.0"; }

FMI2_EXPORT fmi2Component fmi2Instantiate(fmi2String instanceName, fmi2Type fmuType, fmi2String fmuGUID,
                                          fmi2String fmuResourceLocation, const fmi2CallbackFunctions *functions,
                                          fmi2Boolean visible, fmi2Boolean loggingOn) {
    (void)visible;
    Instance tmp;
    memset(&tmp, 0, sizeof tmp);
    tmp.magic = INSTANCE_MAGIC;
    tmp.logger = functions ? functions->logger : NULL;
    tmp.env = functions ? functions->componentEnvironment : NULL;
    tmp.name = (char *)(instanceName ? instanceName : "");
    tmp.logging_on = loggingOn;
    if (!functions || !functions->logger) return NULL; /* FMI 2.0: the logger is required */
    if (!instanceName || !*instanceName) {
        fmu_log(&tmp, fmi2Error, "fmi2Instantiate: instanceName is empty; allowed: a non-empty name");
        return NULL;
    }
    if (fmuType != fmi2CoSimulation) {
        fmu_log(&tmp, fmi2Error, "fmi2Instantiate: fmuType = %d is invalid; allowed: %d (fmi2CoSimulation, "
                "the only interface of this FMU)", (int)fmuType, (int)fmi2CoSimulation);
        return NULL;
    }
    char dir[4096];
    if (!fmuResourceLocation || uri_to_path(fmuResourceLocation, dir, sizeof dir) != 0) {
        fmu_log(&tmp, fmi2Error, "fmi2Instantiate: fmuResourceLocation = '%s' is invalid; allowed: the URI of the "
                "FMU's resources folder (file:///...)", fmuResourceLocation ? fmuResourceLocation : "(null)");
        return NULL;
    }
    Instance *c = (Instance *)calloc(1, sizeof *c);
    if (!c) return NULL;
    *c = tmp;
    size_t len = strlen(instanceName);
    c->name = (char *)malloc(len + 1);
    if (!c->name) {
        free(c);
        return NULL;
    }
    memcpy(c->name, instanceName, len + 1);
    c->mode = MODE_INSTANTIATED;
    c->model = model_new(c, dir, fmuGUID ? fmuGUID : "");
    if (!c->model) {
        c->magic = 0;
        free(c->name);
        free(c);
        return NULL;
    }
    return c;
}

FMI2_EXPORT void fmi2FreeInstance(fmi2Component comp) {
    Instance *c = valid(comp);
    if (!c) return;
    free_all_states(c);
    model_delete(c->model);
    c->magic = 0;
    free(c->name);
    free(c);
}

FMI2_EXPORT fmi2Status fmi2SetDebugLogging(fmi2Component comp, fmi2Boolean loggingOn, size_t nCategories,
                                           const fmi2String categories[]) {
    Instance *c = valid(comp);
    if (!c) return fmi2Error;
    for (size_t i = 0; i < nCategories; i++) {
        const char *cat = categories ? categories[i] : NULL;
        if (!cat || (strcmp(cat, "logInfo") && strcmp(cat, "logWarning") && strcmp(cat, "logDiscard") &&
                     strcmp(cat, "logError"))) {
            fmu_log(c, fmi2Error, "fmi2SetDebugLogging: category '%s' is unknown; allowed: logInfo, logWarning, "
                    "logDiscard, logError", cat ? cat : "(null)");
            return fmi2Error;
        }
    }
    c->logging_on = loggingOn;
    return fmi2OK;
}

FMI2_EXPORT fmi2Status fmi2SetupExperiment(fmi2Component comp, fmi2Boolean toleranceDefined, fmi2Real tolerance,
                                           fmi2Real startTime, fmi2Boolean stopTimeDefined, fmi2Real stopTime) {
    (void)toleranceDefined;
    (void)tolerance;
    CHECK("fmi2SetupExperiment", M(MODE_INSTANTIATED))
    if (!isfinite(startTime) || (stopTimeDefined && !(isfinite(stopTime) && stopTime >= startTime))) {
        fmu_log(c, fmi2Error, "fmi2SetupExperiment: startTime = %.17g, stopTime = %.17g is invalid; allowed: finite, "
                "stopTime >= startTime", startTime, stopTime);
        return fmi2Error;
    }
    c->t_start = startTime;
    return fmi2OK;
}

FMI2_EXPORT fmi2Status fmi2EnterInitializationMode(fmi2Component comp) {
    CHECK("fmi2EnterInitializationMode", M(MODE_INSTANTIATED))
    c->mode = MODE_INIT;
    return fmi2OK;
}

FMI2_EXPORT fmi2Status fmi2ExitInitializationMode(fmi2Component comp) {
    CHECK("fmi2ExitInitializationMode", M(MODE_INIT))
    char err[2048] = "";
    int st = model_initialize(c, c->model, c->t_start, err, sizeof err);
    if (st >= fmi2Error) {
        c->mode = MODE_FAILED;
        snprintf(c->failure, sizeof c->failure, "%s", err);
        fmu_log(c, fmi2Error, "fmi2ExitInitializationMode: initialisation failed: %s", err);
        return fmi2Error;
    }
    c->mode = MODE_STEP;
    return (fmi2Status)st;
}

FMI2_EXPORT fmi2Status fmi2Terminate(fmi2Component comp) {
    CHECK("fmi2Terminate", M(MODE_STEP) | M(MODE_INIT) | M(MODE_FAILED) | M(MODE_INSTANTIATED))
    c->mode = MODE_TERMINATED;
    return fmi2OK;
}

FMI2_EXPORT fmi2Status fmi2Reset(fmi2Component comp) {
    Instance *c = valid(comp);
    if (!c) return fmi2Error;
    model_reset(c->model);
    c->mode = MODE_INSTANTIATED;
    c->t_start = 0.0;
    c->failure[0] = 0;
    return fmi2OK;
}

/* ---- variables ------------------------------------------------------------------------------------------------ */
static const char *TYPE_NAME[] = {"Real", "Integer", "Boolean", "String"};

static int lookup(Instance *c, const char *fn, fmi2ValueReference vr, int type, VarInfo *info) {
    if (!model_var(c->model, vr, info)) {
        fmu_log(c, fmi2Error, "%s: unknown value reference %u", fn, vr);
        return 0;
    }
    if (info->type != type) {
        fmu_log(c, fmi2Error, "%s: value reference %u (%s) is a %s, not a %s", fn, vr, info->name,
                TYPE_NAME[info->type], TYPE_NAME[type]);
        return 0;
    }
    return 1;
}

static int check_get(Instance *c, const char *fn, size_t nvr, const fmi2ValueReference *vr, const void *value,
                     int type) {
    if (c->mode == MODE_FAILED) {
        fmu_log(c, fmi2Error, "%s: no values: the initialisation failed (%s)", fn, c->failure);
        return 0;
    }
    if (nvr && (!vr || !value)) {
        fmu_log(c, fmi2Error, "%s: NULL argument", fn);
        return 0;
    }
    for (size_t i = 0; i < nvr; i++) {
        VarInfo info;
        if (!lookup(c, fn, vr[i], type, &info)) return 0;
        if (c->mode == MODE_INSTANTIATED && info.causality == VC_OUTPUT) {
            fmu_log(c, fmi2Error, "%s: %s is an output: it is computed by fmi2ExitInitializationMode", fn, info.name);
            return 0;
        }
    }
    return 1;
}

/* every value reference known and settable now (all or nothing) */
static int check_set(Instance *c, const char *fn, size_t nvr, const fmi2ValueReference *vr, const void *value,
                     int type) {
    if (c->mode == MODE_FAILED || c->mode == MODE_TERMINATED) {
        fmu_log(c, fmi2Error, "%s: cannot set values: %s", fn,
                c->mode == MODE_TERMINATED ? "after fmi2Terminate" : "the initialisation failed");
        return 0;
    }
    if (nvr && (!vr || !value)) {
        fmu_log(c, fmi2Error, "%s: NULL argument", fn);
        return 0;
    }
    for (size_t i = 0; i < nvr; i++) {
        VarInfo info;
        if (!lookup(c, fn, vr[i], type, &info)) return 0;
        if (info.causality == VC_OUTPUT) {
            fmu_log(c, fmi2Error, "%s: %s is an output (%s); it cannot be set", fn, info.name,
                    type == VT_REAL ? "continuous" : "discrete");
            return 0;
        }
        if (info.causality == VC_PARAMETER && c->mode == MODE_STEP) {
            char v[600];
            model_value_text(c->model, vr[i], v, sizeof v);
            fmu_log(c, fmi2Error, "%s: %s is a fixed parameter: it can only be set before fmi2ExitInitializationMode "
                    "(it stays %s; to change it, fmi2Reset or instantiate anew)", fn, info.name, v);
            return 0;
        }
    }
    return 1;
}

#define ANY_GET (M(MODE_INSTANTIATED) | M(MODE_INIT) | M(MODE_STEP) | M(MODE_TERMINATED) | M(MODE_FAILED))

/* fmi2Get<Type> and fmi2Set<Type>: the checks above, then the model's getter or setter per value reference (a
   set is all or nothing up to the model's own refusal, which is logged) */
#define GETTER(FN, CTYPE, VT, GET)                                                                            \
    FMI2_EXPORT fmi2Status FN(fmi2Component comp, const fmi2ValueReference vr[], size_t nvr, CTYPE value[]) { \
        CHECK(#FN, ANY_GET)                                                                                   \
        if (!check_get(c, #FN, nvr, vr, value, VT)) return fmi2Error;                                        \
        for (size_t i = 0; i < nvr; i++) value[i] = GET(c->model, vr[i]);                                   \
        return fmi2OK;                                                                                        \
    }
GETTER(fmi2GetReal, fmi2Real, VT_REAL, model_get_real)
GETTER(fmi2GetInteger, fmi2Integer, VT_INTEGER, model_get_integer)
GETTER(fmi2GetBoolean, fmi2Boolean, VT_BOOLEAN, model_get_boolean)
GETTER(fmi2GetString, fmi2String, VT_STRING, model_get_string)

#define ANY_SET (M(MODE_INSTANTIATED) | M(MODE_INIT) | M(MODE_STEP) | M(MODE_TERMINATED) | M(MODE_FAILED))
#define SETTER(FN, CTYPE, VT, SET, NULLCHECK)                                                                       \
    FMI2_EXPORT fmi2Status FN(fmi2Component comp, const fmi2ValueReference vr[], size_t nvr, const CTYPE value[]) { \
        CHECK(#FN, ANY_SET)                                                                                         \
        if (!check_set(c, #FN, nvr, vr, value, VT)) return fmi2Error;                                              \
        for (size_t i = 0; i < nvr && NULLCHECK; i++)                                                              \
            if (!value[i]) {                                                                                       \
                fmu_log(c, fmi2Error, "%s: value %lu is NULL; allowed: a string", #FN, (unsigned long)i);          \
                return fmi2Error;                                                                                  \
            }                                                                                                      \
        char err[1024];                                                                                            \
        for (size_t i = 0; i < nvr; i++)                                                                           \
            if (SET(c->model, vr[i], value[i], err, sizeof err)) {                                                 \
                fmu_log(c, fmi2Error, "%s: %s", #FN, err);                                                         \
                return fmi2Error;                                                                                  \
            }                                                                                                      \
        return fmi2OK;                                                                                             \
    }
SETTER(fmi2SetReal, fmi2Real, VT_REAL, model_set_real, 0)
SETTER(fmi2SetInteger, fmi2Integer, VT_INTEGER, model_set_integer, 0)
SETTER(fmi2SetBoolean, fmi2Boolean, VT_BOOLEAN, model_set_boolean, 0)
SETTER(fmi2SetString, fmi2String, VT_STRING, model_set_string, 1)

/* ---- co-simulation ------------------------------------------------------------------------------------------ */
FMI2_EXPORT fmi2Status fmi2DoStep(fmi2Component comp, fmi2Real currentCommunicationPoint,
                                  fmi2Real communicationStepSize, fmi2Boolean noSetFMUStatePriorToCurrentPoint) {
    (void)noSetFMUStatePriorToCurrentPoint;
    Instance *c = valid(comp);
    if (!c) return fmi2Error;
    if (c->mode != MODE_STEP) {
        if (c->mode == MODE_FAILED)
            fmu_log(c, fmi2Error, "fmi2DoStep: not allowed: the initialisation failed (%s)", c->failure);
        else if (c->mode == MODE_TERMINATED)
            fmu_log(c, fmi2Error, "fmi2DoStep: not allowed: after fmi2Terminate");
        else
            fmu_log(c, fmi2Error, "fmi2DoStep: not allowed: the FMU is in %s mode, call fmi2ExitInitializationMode "
                    "first", MODE_NAME[c->mode]);
        return fmi2Error;
    }
    char err[4096] = "";
    int st = model_step(c, c->model, currentCommunicationPoint, communicationStepSize, err, sizeof err);
    if (st == fmi2Discard)
        fmu_log(c, fmi2Discard, "step at t = %.9g s rejected: %s", currentCommunicationPoint, err);
    else if (st >= fmi2Error)
        fmu_log(c, fmi2Error, "step at t = %.9g s failed: %s", currentCommunicationPoint, err);
    return (fmi2Status)st;
}

FMI2_EXPORT fmi2Status fmi2CancelStep(fmi2Component comp) {
    Instance *c = valid(comp);
    if (!c) return fmi2Error;
    fmu_log(c, fmi2Error, "fmi2CancelStep: not supported: fmi2DoStep always completes before it returns "
            "(canRunAsynchronuously = false)");
    return fmi2Error;
}

static fmi2Status no_status(fmi2Component comp, const char *fn) {
    Instance *c = valid(comp);
    if (!c) return fmi2Error;
    fmu_log(c, fmi2Discard, "%s: no status of this kind: fmi2DoStep completes synchronously", fn);
    return fmi2Discard;
}
FMI2_EXPORT fmi2Status fmi2GetStatus(fmi2Component c, const fmi2StatusKind s, fmi2Status *value) {
    (void)s;
    (void)value;
    return no_status(c, "fmi2GetStatus");
}
FMI2_EXPORT fmi2Status fmi2GetRealStatus(fmi2Component comp, const fmi2StatusKind s, fmi2Real *value) {
    Instance *c = valid(comp);
    if (c && s == fmi2LastSuccessfulTime && value && c->mode == MODE_STEP) {
        *value = model_time(c->model);
        return fmi2OK;
    }
    return no_status(comp, "fmi2GetRealStatus");
}
FMI2_EXPORT fmi2Status fmi2GetIntegerStatus(fmi2Component c, const fmi2StatusKind s, fmi2Integer *value) {
    (void)s;
    (void)value;
    return no_status(c, "fmi2GetIntegerStatus");
}
FMI2_EXPORT fmi2Status fmi2GetBooleanStatus(fmi2Component comp, const fmi2StatusKind s, fmi2Boolean *value) {
    Instance *c = valid(comp);
    if (c && s == fmi2Terminated && value) {
        *value = fmi2False;
        return fmi2OK;
    }
    return no_status(comp, "fmi2GetBooleanStatus");
}
FMI2_EXPORT fmi2Status fmi2GetStringStatus(fmi2Component c, const fmi2StatusKind s, fmi2String *value) {
    (void)s;
    (void)value;
    return no_status(c, "fmi2GetStringStatus");
}

static fmi2Status unsupported(fmi2Component comp, const char *fn, const char *why) {
    Instance *c = valid(comp);
    if (!c) return fmi2Error;
    fmu_log(c, fmi2Error, "%s is not supported by this FMU (%s); the instance is unchanged and stays usable", fn, why);
    return fmi2Error;
}
FMI2_EXPORT fmi2Status fmi2SetRealInputDerivatives(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                                                   const fmi2Integer order[], const fmi2Real value[]) {
    (void)vr, (void)nvr, (void)order, (void)value;
    return unsupported(c, "fmi2SetRealInputDerivatives", "canInterpolateInputs = false");
}
FMI2_EXPORT fmi2Status fmi2GetRealOutputDerivatives(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                                                    const fmi2Integer order[], fmi2Real value[]) {
    (void)vr, (void)nvr, (void)order, (void)value;
    return unsupported(c, "fmi2GetRealOutputDerivatives", "maxOutputDerivativeOrder = 0");
}
/* FMI 2.0 section 2.1.9, co-simulation: the derivatives of Real outputs with respect to Real inputs at the last
   communication point (the model gives them: model_directional_derivative) */
FMI2_EXPORT fmi2Status fmi2GetDirectionalDerivative(fmi2Component comp, const fmi2ValueReference vUnknown[],
                                                    size_t nU, const fmi2ValueReference vKnown[], size_t nK,
                                                    const fmi2Real dvKnown[], fmi2Real dvUnknown[]) {
    const char *fn = "fmi2GetDirectionalDerivative";
    Instance *c = valid(comp);
    if (!c) return fmi2Error;
    if (c->mode != MODE_STEP) {
        fmu_log(c, fmi2Error, "%s: not allowed in %s mode; allowed after fmi2ExitInitializationMode (the derivatives "
                "are those of the last communication point)", fn, MODE_NAME[c->mode]);
        return fmi2Error;
    }
    if ((nU && (!vUnknown || !dvUnknown)) || (nK && (!vKnown || !dvKnown))) {
        fmu_log(c, fmi2Error, "%s: a NULL array with nUnknown = %lu, nKnown = %lu", fn, (unsigned long)nU,
                (unsigned long)nK);
        return fmi2Error;
    }
    VarInfo info;
    for (size_t k = 0; k < nK; k++)
        if (!model_var(c->model, vKnown[k], &info) || info.type != VT_REAL || info.causality != VC_INPUT) {
            fmu_log(c, fmi2Error, "%s: vKnown_ref[%lu] = %u is not a Real input; allowed: the inputs", fn,
                    (unsigned long)k, vKnown[k]);
            return fmi2Error;
        }
    for (size_t k = 0; k < nU; k++)
        if (!model_var(c->model, vUnknown[k], &info) || info.type != VT_REAL || info.causality != VC_OUTPUT) {
            fmu_log(c, fmi2Error, "%s: vUnknown_ref[%lu] = %u is not a Real output; allowed: the outputs", fn,
                    (unsigned long)k, vUnknown[k]);
            return fmi2Error;
        }
    char err[1024];
    if (model_directional_derivative(c->model, vUnknown, nU, vKnown, nK, dvKnown, dvUnknown, err, sizeof err)) {
        fmu_log(c, fmi2Error, "%s: %s", fn, err);
        return fmi2Error;
    }
    return fmi2OK;
}

/* ---- FMU states ------------------------------------------------------------------------------------------------
 * An FMU state is the layer's mode and the model's mutable state (model_state_save). Serialised:
 *   char[8] "BRGSTATE", u32 version, u32 header size (96), u32 mode, u32 payload size, u32 CRC-32 of the payload,
 *   u32 length of the GUID, char[64] the model's GUID (zero-padded, cut at 64 bytes), then the payload.
 * Deserialising checks every header field, the GUID, the CRC and then the payload field by field (model). */
typedef struct FmuState {
    unsigned magic;
    int mode;
    size_t size;
    unsigned char *bytes;
    struct FmuState *next; /* the instance's list of states */
    Instance *owner;
} FmuState;

static FmuState *new_state(Instance *c) {
    FmuState *st = (FmuState *)calloc(1, sizeof *st);
    if (!st) return NULL;
    st->magic = STATE_MAGIC;
    st->owner = c;
    st->next = (FmuState *)c->states;
    c->states = st;
    return st;
}

static void free_state(Instance *c, FmuState *st) {
    for (FmuState **p = (FmuState **)&c->states; *p; p = &(*p)->next)
        if (*p == st) {
            *p = st->next;
            break;
        }
    st->magic = 0;
    free(st->bytes);
    free(st);
}

static void free_all_states(Instance *c) {
    while (c->states) free_state(c, (FmuState *)c->states);
}

/* a state this instance allocated (and has not freed) */
static FmuState *valid_state(Instance *c, fmi2FMUstate s) {
    for (FmuState *st = (FmuState *)c->states; st; st = st->next)
        if (st == (FmuState *)s && st->magic == STATE_MAGIC && st->owner == c) return st;
    return NULL;
}

FMI2_EXPORT fmi2Status fmi2GetFMUstate(fmi2Component comp, fmi2FMUstate *FMUstate) {
    CHECK("fmi2GetFMUstate", M(MODE_INIT) | M(MODE_STEP))
    if (!FMUstate) {
        fmu_log(c, fmi2Error, "fmi2GetFMUstate: NULL argument");
        return fmi2Error;
    }
    size_t n = model_state_size(c->model);
    FmuState *st = valid_state(c, *FMUstate);
    if (!st) {
        st = new_state(c);
        if (!st) return fmi2Error;
    }
    if (st->size != n) {
        unsigned char *b = (unsigned char *)realloc(st->bytes, n ? n : 1);
        if (!b) return fmi2Error;
        st->bytes = b;
        st->size = n;
    }
    model_state_save(c->model, st->bytes);
    st->mode = c->mode;
    *FMUstate = st;
    return fmi2OK;
}

FMI2_EXPORT fmi2Status fmi2SetFMUstate(fmi2Component comp, fmi2FMUstate FMUstate) {
    CHECK("fmi2SetFMUstate", M(MODE_INIT) | M(MODE_STEP))
    FmuState *st = valid_state(c, FMUstate);
    if (!st) {
        fmu_log(c, fmi2Error, "fmi2SetFMUstate: not an FMU state of this FMU");
        return fmi2Error;
    }
    char err[512];
    if (model_state_load(c->model, st->bytes, st->size, err, sizeof err)) {
        fmu_log(c, fmi2Error, "fmi2SetFMUstate: %s", err);
        return fmi2Error;
    }
    c->mode = st->mode;
    return fmi2OK;
}

FMI2_EXPORT fmi2Status fmi2FreeFMUstate(fmi2Component comp, fmi2FMUstate *FMUstate) {
    Instance *c = valid(comp);
    if (!c) return fmi2Error;
    if (!FMUstate || !*FMUstate) return fmi2OK;
    FmuState *st = valid_state(c, *FMUstate);
    if (!st) {
        fmu_log(c, fmi2Error, "fmi2FreeFMUstate: not an FMU state of this FMU");
        return fmi2Error;
    }
    free_state(c, st);
    *FMUstate = NULL;
    return fmi2OK;
}

FMI2_EXPORT fmi2Status fmi2SerializedFMUstateSize(fmi2Component comp, fmi2FMUstate FMUstate, size_t *size) {
    Instance *c = valid(comp);
    if (!c) return fmi2Error;
    FmuState *st = valid_state(c, FMUstate);
    if (!st || !size) {
        fmu_log(c, fmi2Error, "fmi2SerializedFMUstateSize: not an FMU state of this FMU");
        return fmi2Error;
    }
    *size = SER_HEADER + st->size;
    return fmi2OK;
}

FMI2_EXPORT fmi2Status fmi2SerializeFMUstate(fmi2Component comp, fmi2FMUstate FMUstate, fmi2Byte serializedState[],
                                             size_t size) {
    Instance *c = valid(comp);
    if (!c) return fmi2Error;
    FmuState *st = valid_state(c, FMUstate);
    if (!st || !serializedState) {
        fmu_log(c, fmi2Error, "fmi2SerializeFMUstate: not an FMU state of this FMU");
        return fmi2Error;
    }
    if (size < SER_HEADER + st->size) {
        fmu_log(c, fmi2Error, "fmi2SerializeFMUstate: size = %zu is too small; allowed: >= %zu "
                "(fmi2SerializedFMUstateSize)", size, (size_t)(SER_HEADER + st->size));
        return fmi2Error;
    }
    unsigned char *p = (unsigned char *)serializedState;
    memset(p, 0, SER_HEADER);
    memcpy(p, SER_MAGIC, 8);
    le_put_u32(p + 8, SER_VERSION);
    le_put_u32(p + 12, SER_HEADER);
    le_put_u32(p + 16, (unsigned)st->mode);
    le_put_u32(p + 20, (unsigned)st->size);
    le_put_u32(p + 24, crc32_ieee(st->bytes, st->size));
    const char *g = model_guid(c->model);
    size_t gl = strlen(g) > 64 ? 64 : strlen(g);
    le_put_u32(p + 28, (unsigned)gl);
    memcpy(p + 32, g, gl);
    memcpy(p + SER_HEADER, st->bytes, st->size);
    return fmi2OK;
}

FMI2_EXPORT fmi2Status fmi2DeSerializeFMUstate(fmi2Component comp, const fmi2Byte serializedState[], size_t size,
                                               fmi2FMUstate *FMUstate) {
    Instance *c = valid(comp);
    if (!c) return fmi2Error;
    const unsigned char *p = (const unsigned char *)serializedState;
    const char *why = NULL;
    char buf[256];
    size_t n = 0;
    if (!p || !FMUstate)
        why = "NULL argument";
    else if (size < SER_HEADER || memcmp(p, SER_MAGIC, 8))
        why = "not a serialized state of this FMU (no BRGSTATE header)";
    else if (le_get_u32(p + 8) != SER_VERSION) {
        snprintf(buf, sizeof buf, "serialized state of format version %u; this FMU reads version %u", le_get_u32(p + 8),
                 SER_VERSION);
        why = buf;
    } else if (le_get_u32(p + 12) != SER_HEADER)
        why = "corrupt serialized state (header size)";
    else if (le_get_u32(p + 16) != MODE_INIT && le_get_u32(p + 16) != MODE_STEP)
        why = "corrupt serialized state (mode)";
    else if ((n = le_get_u32(p + 20)) != size - SER_HEADER) {
        snprintf(buf, sizeof buf, "serialized state of %zu bytes with a payload of %zu bytes: truncated or padded",
                 size, n);
        why = buf;
    } else if (n != model_state_size(c->model))
        why = "serialized state of another model (payload size)";
    else if (crc32_ieee(p + SER_HEADER, n) != le_get_u32(p + 24))
        why = "corrupt serialized state (CRC-32 mismatch)";
    else {
        const char *g = model_guid(c->model);
        size_t gl = strlen(g) > 64 ? 64 : strlen(g);
        if (le_get_u32(p + 28) != gl || memcmp(p + 32, g, gl)) why = "serialized state of another FMU (GUID)";
    }
    if (why) {
        fmu_log(c, fmi2Error, "fmi2DeSerializeFMUstate: %s", why);
        return fmi2Error;
    }
    /* the payload checked field by field on a scratch model state: the instance is unchanged if it is refused */
    char err[512];
    size_t cur = model_state_size(c->model);
    unsigned char *keep = (unsigned char *)malloc(cur ? cur : 1);
    if (!keep) return fmi2Error;
    model_state_save(c->model, keep);
    if (model_state_load(c->model, p + SER_HEADER, n, err, sizeof err)) {
        model_state_load(c->model, keep, cur, buf, sizeof buf);
        free(keep);
        fmu_log(c, fmi2Error, "fmi2DeSerializeFMUstate: %s", err);
        return fmi2Error;
    }
    model_state_load(c->model, keep, cur, buf, sizeof buf);
    free(keep);
    FmuState *st = new_state(c);
    if (!st) return fmi2Error;
    st->bytes = (unsigned char *)malloc(n ? n : 1);
    if (!st->bytes) {
        free_state(c, st);
        return fmi2Error;
    }
    memcpy(st->bytes, p + SER_HEADER, n);
    st->size = n;
    st->mode = (int)le_get_u32(p + 16);
    *FMUstate = st;
    return fmi2OK;
}
