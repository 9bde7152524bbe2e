/* The shared FMI 2.0 co-simulation layer of the pure-C FMUs (Reference-FMUs' split): fmi2_common.c implements
 * every fmi2* function (argument checks, the state machine of FMI 2.0 section 4.3, logging, FMU states and their
 * serialisation, the resource location) and calls the model through the functions declared at the end of this
 * header, which each FMU kind implements in its own folder (map/model.c). The layer never knows a model's
 * internals and a model never touches FMI calls.
 *
 * C99, libc and libm only; no globals: every instance is independent and may run on any thread.
 */
#ifndef BEARING_FMI2_COMMON_H
#define BEARING_FMI2_COMMON_H
#include <stddef.h>

/* the FMI 2.0 types, callbacks and export macro: shared with the native layer of BearingFMU (native/) */
#include "fmi2_min.h"

/* ---- the instance (owned by the layer) ------------------------------------------------------------------ */
enum { MODE_INSTANTIATED, MODE_INIT, MODE_STEP, MODE_TERMINATED, MODE_FAILED };

typedef struct Instance {
    unsigned magic;
    fmi2CallbackLogger logger;
    fmi2ComponentEnvironment env;
    char *name;
    int logging_on;
    int mode;
    double t_start;
    char failure[2048]; /* why the initialisation failed (MODE_FAILED) */
    void *model;
    void *states; /* the FMU states this instance allocated (freed with it, FMI 2.0 fmi2FreeInstance) */
} Instance;

/* The message (printf format) to the master's logger, category from the status (logInfo only with logging on). */
void fmu_log(Instance *c, int status, const char *fmt, ...)
#if defined(__MINGW32__)
    __attribute__((format(gnu_printf, 3, 4))) /* C99 formats (__USE_MINGW_ANSI_STDIO) */
#elif defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

/* ---- what a model implements ---------------------------------------------------------------------------- */
enum { VT_REAL, VT_INTEGER, VT_BOOLEAN, VT_STRING };
enum { VC_PARAMETER, VC_INPUT, VC_OUTPUT };

typedef struct {
    const char *name;
    int type;      /* VT_* */
    int causality; /* VC_* (parameters are fixed: settable before fmi2ExitInitializationMode only) */
} VarInfo;

/* A new model from its resources folder (a file-system path), or NULL with the reason logged. */
void *model_new(Instance *c, const char *resource_dir, const char *guid);
void model_delete(void *m);
/* parameters and inputs back to their start values, time and state as after model_new */
void model_reset(void *m);
/* 1 and its description if vr is a variable of the model, else 0 */
int model_var(void *m, fmi2ValueReference vr, VarInfo *info);
double model_get_real(void *m, fmi2ValueReference vr);
int model_get_integer(void *m, fmi2ValueReference vr);
int model_get_boolean(void *m, fmi2ValueReference vr);
const char *model_get_string(void *m, fmi2ValueReference vr);
/* the value for vr (a known variable of that type); 0, or -1 with the reason in err */
int model_set_real(void *m, fmi2ValueReference vr, double v, char *err, size_t n);
int model_set_integer(void *m, fmi2ValueReference vr, int v, char *err, size_t n);
int model_set_boolean(void *m, fmi2ValueReference vr, int v, char *err, size_t n);
int model_set_string(void *m, fmi2ValueReference vr, const char *v, char *err, size_t n);
/* the value as the model prints it in messages (Python repr) */
void model_value_text(void *m, fmi2ValueReference vr, char *buf, size_t n);
/* fmi2ExitInitializationMode: OK or Warning (messages logged), or Error with the reason in err */
int model_initialize(Instance *c, void *m, double t0, char *err, size_t n);
/* fmi2DoStep: OK, Warning (logged), or Discard / Error with the reason in err; the model state is unchanged
   unless the step succeeds */
int model_step(Instance *c, void *m, double t, double h, char *err, size_t n);
double model_time(void *m);
/* fmi2GetDirectionalDerivative: df = J dv, J = d(unknowns z)/d(knowns u) at the last communication point (z Real
   outputs, u Real inputs, checked by the layer); 0, or -1 with the reason in err */
int model_directional_derivative(void *m, const fmi2ValueReference *z, size_t nz, const fmi2ValueReference *u,
                                 size_t nu, const double *dv, double *df, char *err, size_t n);
/* the model's guid (FMU states carry it) */
const char *model_guid(void *m);
/* the mutable state as little-endian bytes of model_state_size(m) bytes, and back (0, or -1 with the reason) */
size_t model_state_size(void *m);
void model_state_save(void *m, unsigned char *buf);
int model_state_load(void *m, const unsigned char *buf, size_t size, char *err, size_t n);

/* ---- little-endian byte helpers (tables, states) --------------------------------------------------------- */
void le_put_u32(unsigned char *p, unsigned v);
void le_put_f64(unsigned char *p, double v);
unsigned le_get_u32(const unsigned char *p);
double le_get_f64(const unsigned char *p);
unsigned crc32_ieee(const unsigned char *p, size_t n);
/* the path of a file URI (file:///C:/a%20b, file:/x, file://localhost/x) or a plain path; 0, or -1 */
int uri_to_path(const char *uri, char *out, size_t n);
/* Python's repr of a float (shortest round-trip digits: 0.1, 1e-05, 3000.0, nan, inf) */
void py_repr_double(double v, char *buf, size_t n);
/* Python's repr of a str ('abc', "it's") */
void py_repr_string(const char *s, char *buf, size_t n);

#endif
