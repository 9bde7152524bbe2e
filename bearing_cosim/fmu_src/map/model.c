/* The 'map' fidelity level of the bearing in C: an operating map of `bearing build-map` (resources/map_table.bin,
 * written by bearing_cosim/map_table.py, format documented there) interpolated multilinearly, never extrapolated,
 * with the first-order lag of the cage speed and the acceleration torque of balls and cage.
 *
 * The arithmetic is that of bearing_core.session.map_kernels (interp_multilinear, steady_level_outputs, map_step)
 * and the checks and messages those of bearing_core.session.fidelity (MapLevel.query, range_error,
 * _check_parameters; SteadySession.step, initialize, _note_flags), statement for statement, so that this FMU
 * and BearingFMU at fidelity = map give the same outputs, statuses and messages.
 *
 * What the level is: the steady outputs of the dynamic model (window means at each grid point), read at the held
 * inputs; the cage speed follows its steady value through a first-order lag with the map's own time constant.
 * What it is not: no displacement coupling, no oil supply (the cavity oil content is a parameter of the map), no
 * thermal network (isothermal at the map's oil temperature), no per-ball outputs (ball0_* and ir_ax hold 0).
 *
 * fmi2DoStep allocates nothing and iterates nothing: a bisection per axis, 2^n_axes cell corners, one pass over
 * the outputs. No globals. C99, libc and libm.
 */
#if defined(_WIN32) && !defined(__USE_MINGW_ANSI_STDIO)
#define __USE_MINGW_ANSI_STDIO 1
#endif
#include "fmi2_common.h"
#include "config.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define TABLE_MAGIC "BRGMAPTB"
#define TABLE_HEADER 64u
#define END_MARK 0x454E4421u
#define MAX_AXES 8
#define MAX_VALS 512
#define MAX_OUT 1024
#define MAX_IN 64
#define MAX_PAR 128
#define MAX_POINTS 20000000u
#define STR_CAP 512 /* longest String parameter value + 1 */
#define N_IB 19
#define N_TEMPS 7
#define STATE_VERSION 1u
#define FLAG_GROSS_SKID 1
#define FLAG_CAGE_UNSTEADY 2

enum { CHECK_BUILT, CHECK_FIXED, CHECK_FIDELITY, CHECK_MAP_FILE, CHECK_OIL_AXIS, CHECK_NONE, CHECK_ENUM };

typedef struct {
    char *name, *start_str, *repr, *detail;
    char **alt;
    int type, check, n_alt;
    double start;
    /* the current value */
    double num;
    char str[STR_CAP];
} Param;

typedef struct {
    char *name;
    int kind, input;
    double fixed, lo, hi, tol;
    int n, off; /* values in axes[off:off + n] */
} Axis;

typedef struct {
    /* ---- the table (read-only after model_new) ---- */
    char *guid, *level, *bearing, *map_name, *provenance, *path;
    int n_in, n_out_real, n_out_int, n_out, n_axes, n_vals, n_points;
    char **in_names;
    double in_start[MAX_IN];
    char *flag_text[2]; /* MapLevel.FLAG_TEXT of FLAG_GROSS_SKID, FLAG_CAGE_UNSTEADY */
    int has_k, i_k;     /* the map holds the stiffness; the output index of stiffness[1,1] */
    double *kvals;      /* n_points x 25: K = d(load)/d(pose) at each grid point, row-major */
    char *stiffness_missing;
    /* the fatigue outputs (SteadySession._life_into): the damage rate's index in the values (-1: the map has none,
       life_L10r_h and fatigue_damage hold 0), their output indices, the life reported for an infinite one [h] */
    int i_rate, i_life, i_damage;
    double life_cap;
    char *fatigue_missing;
    int o_reac[5], o_ir[5], i_load[5]; /* reaction_Fx..My, ir_x..ir_ty, inputs Fx..My (directional derivative) */
    int i_speed, i_fx, i_fy, i_oring, rotate, n_zero;
    int zero_in[MAX_IN];
    Axis ax[MAX_AXES];
    double *axes;
    int i_axis_oil;
    double rpm;
    char **val_names;
    int *speed_scaled;
    int i_tau;
    double *values; /* n_points x n_vals */
    int *flags;
    long long strides[MAX_AXES];
    char **out_names;
    int *src;
    int n_rot;
    int *rot;
    int ib[N_IB];
    double temps[N_TEMPS], inertia, csr_min, skid_tol, skid_min;
    int i_oil;
    double oil_fraction;
    int n_par;
    Param par[MAX_PAR];
    /* ---- mutable state (model_state_save) ---- */
    double u[MAX_IN];
    double t, wc, w_prev;
    int last_flags;
    double *out; /* n_out: the outputs at the last communication point */
    /* ---- work (no allocation per step) ---- */
    double *new_out, *ss, kbuf[25];
    int defer;              /* initialisation: the flags' warning waits in pending (logged after the others) */
    char pending[2048];
    double x[MAX_AXES], w[MAX_AXES];
    int idx[MAX_AXES];
} Model;

/* ---- table reader ------------------------------------------------------------------------------------------ */
typedef struct {
    const unsigned char *p;
    size_t n, off;
    char err[512];
} Rd;

static int need(Rd *r, size_t k, const char *what) {
    if (r->err[0]) return 0;
    if (k > r->n - r->off) {
        snprintf(r->err, sizeof r->err, "truncated table: %s at byte %zu needs %zu bytes, %zu left", what, r->off, k,
                 r->n - r->off);
        return 0;
    }
    return 1;
}
static unsigned rd_u32(Rd *r, const char *what) {
    if (!need(r, 4, what)) return 0;
    unsigned v = le_get_u32(r->p + r->off);
    r->off += 4;
    return v;
}
static int rd_i32(Rd *r, const char *what) { return (int)(int32_t)rd_u32(r, what); }
static double rd_f64(Rd *r, const char *what) {
    if (!need(r, 8, what)) return 0.0;
    double v = le_get_f64(r->p + r->off);
    r->off += 8;
    return v;
}
static char *rd_str(Rd *r, const char *what) {
    unsigned len = rd_u32(r, what);
    if (r->err[0]) return NULL;
    if (len > (1u << 24)) {
        snprintf(r->err, sizeof r->err, "corrupt table: %s has length %u", what, len);
        return NULL;
    }
    if (!need(r, len, what)) return NULL;
    char *s = (char *)malloc((size_t)len + 1);
    if (!s) {
        snprintf(r->err, sizeof r->err, "out of memory reading %s", what);
        return NULL;
    }
    memcpy(s, r->p + r->off, len);
    s[len] = 0;
    if (strlen(s) != len) {
        free(s);
        snprintf(r->err, sizeof r->err, "corrupt table: %s holds a NUL byte", what);
        return NULL;
    }
    r->off += len;
    return s;
}
static double *rd_f64a(Rd *r, size_t n, const char *what) {
    if (n > ((size_t)1 << 31) / 8 || !need(r, n * 8, what)) {
        if (!r->err[0]) snprintf(r->err, sizeof r->err, "corrupt table: %s of %zu values", what, n);
        return NULL;
    }
    double *a = (double *)malloc(n ? n * 8 : 8);
    if (!a) {
        snprintf(r->err, sizeof r->err, "out of memory reading %s", what);
        return NULL;
    }
    for (size_t i = 0; i < n; i++) a[i] = le_get_f64(r->p + r->off + 8 * i);
    r->off += n * 8;
    return a;
}
static int *rd_i32a(Rd *r, size_t n, const char *what) {
    if (n > ((size_t)1 << 31) / 4 || !need(r, n * 4, what)) {
        if (!r->err[0]) snprintf(r->err, sizeof r->err, "corrupt table: %s of %zu values", what, n);
        return NULL;
    }
    int *a = (int *)malloc(n ? n * 4 : 4);
    if (!a) {
        snprintf(r->err, sizeof r->err, "out of memory reading %s", what);
        return NULL;
    }
    for (size_t i = 0; i < n; i++) a[i] = (int)(int32_t)le_get_u32(r->p + r->off + 4 * i);
    r->off += n * 4;
    return a;
}
static int bad(Rd *r, const char *fmt, const char *what, long long v) {
    if (!r->err[0]) {
        char f[256];
        snprintf(f, sizeof f, "corrupt table: %s = %%lld is out of range (%s)", what, fmt);
        snprintf(r->err, sizeof r->err, f, v);
    }
    return 0;
}
#define RANGE(v, lo, hi, what)                                                        \
    do {                                                                              \
        if (!r->err[0] && ((long long)(v) < (long long)(lo) || (long long)(v) > (long long)(hi))) \
            bad(r, #lo " <= value <= " #hi, what, (long long)(v));                    \
    } while (0)

static void free_strs(char **a, int n) {
    if (!a) return;
    for (int i = 0; i < n; i++) free(a[i]);
    free(a);
}

void model_delete(void *mp) {
    Model *m = (Model *)mp;
    if (!m) return;
    free_strs(m->in_names, m->n_in);
    free(m->flag_text[0]), free(m->flag_text[1]);
    free(m->kvals), free(m->stiffness_missing), free(m->fatigue_missing);
    free(m->guid), free(m->level), free(m->bearing), free(m->map_name), free(m->provenance), free(m->path);
    for (int d = 0; d < MAX_AXES; d++) free(m->ax[d].name);
    free(m->axes);
    free_strs(m->val_names, m->n_vals);
    free(m->speed_scaled), free(m->values), free(m->flags);
    free_strs(m->out_names, m->n_out);
    free(m->src), free(m->rot), free(m->out), free(m->new_out), free(m->ss);
    for (int k = 0; k < MAX_PAR; k++) {
        Param *p = &m->par[k];
        free(p->name), free(p->start_str), free(p->repr), free(p->detail);
        free_strs(p->alt, p->n_alt);
    }
    free(m);
}

static int parse_table(Model *m, Rd *r) {
    m->guid = rd_str(r, "guid");
    m->level = rd_str(r, "level");
    m->bearing = rd_str(r, "bearing");
    m->map_name = rd_str(r, "map name");
    m->provenance = rd_str(r, "provenance");
    m->n_in = (int)rd_u32(r, "n_in");
    m->n_out_real = (int)rd_u32(r, "n_out_real");
    m->n_out_int = (int)rd_u32(r, "n_out_int");
    m->n_axes = (int)rd_u32(r, "n_axes");
    m->n_vals = (int)rd_u32(r, "n_vals");
    unsigned npts = rd_u32(r, "n_points");
    RANGE(m->n_in, 1, MAX_IN, "n_in");
    RANGE(m->n_out_real, 1, MAX_OUT, "n_out_real");
    RANGE(m->n_out_int, 0, MAX_OUT, "n_out_int");
    RANGE(m->n_out_real + m->n_out_int, 1, MAX_OUT, "n_out");
    RANGE(m->n_axes, 1, MAX_AXES, "n_axes");
    RANGE(m->n_vals, 1, MAX_VALS, "n_vals");
    RANGE(npts, 1, MAX_POINTS, "n_points");
    if (r->err[0]) return 0;
    m->n_out = m->n_out_real + m->n_out_int;
    m->n_points = (int)npts;
    m->in_names = (char **)calloc((size_t)m->n_in, sizeof(char *));
    if (!m->in_names) return 0;
    for (int k = 0; k < m->n_in && !r->err[0]; k++) m->in_names[k] = rd_str(r, "input name");
    for (int k = 0; k < m->n_in && !r->err[0]; k++) {
        m->in_start[k] = rd_f64(r, "input start");
        if (!r->err[0] && !isfinite(m->in_start[k])) bad(r, "finite", "input start", k);
    }
    m->i_speed = rd_i32(r, "i_speed");
    m->i_fx = rd_i32(r, "i_fx");
    m->i_fy = rd_i32(r, "i_fy");
    m->i_oring = rd_i32(r, "i_oring");
    m->rotate = rd_i32(r, "rotate");
    RANGE(m->i_speed, 0, m->n_in - 1, "i_speed");
    RANGE(m->i_fx, 0, m->n_in - 1, "i_fx");
    RANGE(m->i_fy, 0, m->n_in - 1, "i_fy");
    RANGE(m->i_oring, 0, m->n_in - 1, "i_oring");
    RANGE(m->rotate, 0, 1, "rotate");
    m->n_zero = (int)rd_u32(r, "n_zero");
    RANGE(m->n_zero, 0, m->n_in, "n_zero");
    if (r->err[0]) return 0;
    for (int k = 0; k < m->n_zero; k++) {
        m->zero_in[k] = rd_i32(r, "zero_in");
        RANGE(m->zero_in[k], 0, m->n_in - 1, "zero_in");
    }
    /* axes */
    size_t total = 0;
    const unsigned char *axes_at[MAX_AXES];
    for (int d = 0; d < m->n_axes && !r->err[0]; d++) {
        Axis *a = &m->ax[d];
        a->name = rd_str(r, "axis name");
        a->kind = rd_i32(r, "axis kind");
        a->input = rd_i32(r, "axis input");
        a->fixed = rd_f64(r, "axis fixed value");
        a->lo = rd_f64(r, "axis lo");
        a->hi = rd_f64(r, "axis hi");
        a->tol = rd_f64(r, "axis tol");
        a->n = (int)rd_u32(r, "axis length");
        RANGE(a->kind, 0, 3, "axis kind");
        RANGE(a->n, 1, 1000000, "axis length");
        if (a->kind == 3) RANGE(a->input, 0, m->n_in - 1, "axis input");
        if (r->err[0]) return 0;
        if (!need(r, (size_t)a->n * 8, "axis values")) return 0;
        axes_at[d] = r->p + r->off;
        r->off += (size_t)a->n * 8;
        a->off = (int)total;
        total += (size_t)a->n;
    }
    if (r->err[0]) return 0;
    m->axes = (double *)malloc(total * 8);
    if (!m->axes) return 0;
    long long npoints = 1;
    for (int d = 0; d < m->n_axes; d++) {
        Axis *a = &m->ax[d];
        for (int i = 0; i < a->n; i++) m->axes[a->off + i] = le_get_f64(axes_at[d] + 8 * i);
        const double *v = m->axes + a->off;
        for (int i = 0; i < a->n; i++)
            if (!isfinite(v[i]) || (i > 0 && !(v[i] > v[i - 1]))) {
                snprintf(r->err, sizeof r->err, "corrupt table: axis %s is not finite and increasing at %d", a->name,
                         i);
                return 0;
            }
        if (a->lo != v[0] || a->hi != v[a->n - 1] || !(a->tol >= 0.0) || !isfinite(a->tol)) {
            snprintf(r->err, sizeof r->err, "corrupt table: axis %s range", a->name);
            return 0;
        }
        npoints *= a->n;
    }
    if (npoints != m->n_points) {
        snprintf(r->err, sizeof r->err, "corrupt table: %lld grid points by the axes, %d stated", npoints, m->n_points);
        return 0;
    }
    m->strides[m->n_axes - 1] = 1;
    for (int d = m->n_axes - 2; d >= 0; d--) m->strides[d] = m->strides[d + 1] * m->ax[d + 1].n;
    m->i_axis_oil = rd_i32(r, "i_axis_oil");
    RANGE(m->i_axis_oil, -1, m->n_axes - 1, "i_axis_oil");
    m->rpm = rd_f64(r, "rpm");
    if (!r->err[0] && !(m->rpm > 0.0 && isfinite(m->rpm))) bad(r, "> 0", "rpm", 0);
    if (r->err[0]) return 0;
    m->val_names = (char **)calloc((size_t)m->n_vals, sizeof(char *));
    if (!m->val_names) return 0;
    for (int k = 0; k < m->n_vals && !r->err[0]; k++) m->val_names[k] = rd_str(r, "value name");
    m->speed_scaled = rd_i32a(r, (size_t)m->n_vals, "speed_scaled");
    m->i_tau = rd_i32(r, "i_tau");
    RANGE(m->i_tau, 0, m->n_vals - 1, "i_tau");
    m->values = rd_f64a(r, (size_t)m->n_points * (size_t)m->n_vals, "values");
    m->flags = rd_i32a(r, (size_t)m->n_points, "flags");
    if (r->err[0]) return 0;
    for (int i = 0; i < m->n_points; i++) RANGE(m->flags[i], 0, 3, "flags");
    m->flag_text[0] = rd_str(r, "flag text");
    m->flag_text[1] = rd_str(r, "flag text");
    m->has_k = (int)rd_u32(r, "has_k");
    m->i_k = rd_i32(r, "i_k");
    RANGE(m->has_k, 0, 1, "has_k");
    if (r->err[0]) return 0;
    if (m->has_k) {
        RANGE(m->i_k, 0, m->n_out_real - 25, "i_k");
        m->kvals = rd_f64a(r, (size_t)m->n_points * 25, "stiffness values");
    }
    m->stiffness_missing = rd_str(r, "stiffness warning");
    m->out_names = (char **)calloc((size_t)m->n_out, sizeof(char *));
    if (!m->out_names) return 0;
    for (int k = 0; k < m->n_out && !r->err[0]; k++) m->out_names[k] = rd_str(r, "output name");
    m->src = rd_i32a(r, (size_t)m->n_out, "src");
    if (r->err[0]) return 0;
    for (int k = 0; k < m->n_out; k++) RANGE(m->src[k], -1, m->n_vals - 1, "src");
    m->n_rot = (int)rd_u32(r, "n_rot");
    RANGE(m->n_rot, 0, m->n_out, "n_rot");
    if (r->err[0]) return 0;
    m->rot = rd_i32a(r, (size_t)m->n_rot * 2, "rot");
    if (r->err[0]) return 0;
    for (int k = 0; k < 2 * m->n_rot; k++) RANGE(m->rot[k], 0, m->n_out - 1, "rot");
    unsigned nib = rd_u32(r, "n_ib");
    if (!r->err[0] && nib != N_IB) bad(r, "19", "n_ib", nib);
    for (int k = 0; k < N_IB && !r->err[0]; k++) {
        m->ib[k] = rd_i32(r, "ib");
        RANGE(m->ib[k], 0, (k == 6 ? m->n_vals : m->n_out) - 1, "ib");
    }
    for (int k = 0; k < N_TEMPS; k++) m->temps[k] = rd_f64(r, "temps");
    m->inertia = rd_f64(r, "inertia");
    m->csr_min = rd_f64(r, "csr_min");
    m->skid_tol = rd_f64(r, "skid_tol");
    m->skid_min = rd_f64(r, "skid_min");
    m->i_oil = rd_i32(r, "i_oil");
    RANGE(m->i_oil, -1, m->n_out - 1, "i_oil");
    m->oil_fraction = rd_f64(r, "oil_fraction");
    if (r->err[0]) return 0;
    for (int k = 0; k < N_TEMPS; k++)
        if (!isfinite(m->temps[k])) return bad(r, "finite", "temps", k);
    if (!(isfinite(m->inertia) && m->inertia >= 0.0 && isfinite(m->csr_min) && isfinite(m->skid_tol) &&
          isfinite(m->skid_min) && isfinite(m->oil_fraction)))
        return bad(r, "finite", "output constants", 0);
    m->n_par = (int)rd_u32(r, "n_par");
    RANGE(m->n_par, 0, MAX_PAR, "n_par");
    for (int k = 0; k < m->n_par && !r->err[0]; k++) {
        Param *p = &m->par[k];
        p->name = rd_str(r, "parameter name");
        p->type = rd_i32(r, "parameter type");
        p->check = rd_i32(r, "parameter check");
        p->start = rd_f64(r, "parameter start");
        p->start_str = rd_str(r, "parameter start string");
        p->repr = rd_str(r, "parameter repr");
        p->detail = rd_str(r, "parameter detail");
        p->n_alt = (int)rd_u32(r, "parameter alternatives");
        RANGE(p->type, 0, 3, "parameter type");
        RANGE(p->check, 0, 6, "parameter check");
        RANGE(p->n_alt, 0, 16, "parameter alternatives");
        if (r->err[0]) return 0;
        p->alt = (char **)calloc((size_t)(p->n_alt ? p->n_alt : 1), sizeof(char *));
        if (!p->alt) return 0;
        for (int j = 0; j < p->n_alt && !r->err[0]; j++) p->alt[j] = rd_str(r, "parameter alternative");
        if (!r->err[0] && (!isfinite(p->start) || strlen(p->start_str) >= STR_CAP))
            bad(r, "finite, shorter than 512 bytes", "parameter start", k);
        if (!r->err[0] && p->check == CHECK_OIL_AXIS && (m->i_axis_oil < 0 || p->type != VT_REAL))
            bad(r, "an oil temperature axis", "parameter check", p->check);
    }
    m->i_rate = rd_i32(r, "i_rate");
    m->i_life = rd_i32(r, "i_life");
    m->i_damage = rd_i32(r, "i_damage");
    m->life_cap = rd_f64(r, "life_cap");
    m->fatigue_missing = rd_str(r, "fatigue warning");
    RANGE(m->i_rate, -1, m->n_vals - 1, "i_rate");
    RANGE(m->i_life, 0, m->n_out_real - 1, "i_life");
    RANGE(m->i_damage, 0, m->n_out_real - 1, "i_damage");
    if (!r->err[0] && !(isfinite(m->life_cap) && m->life_cap > 0.0)) bad(r, "finite, > 0", "life_cap", 0);
    unsigned end = rd_u32(r, "end mark");
    if (!r->err[0] && end != END_MARK) bad(r, "the end mark", "end mark", end);
    if (!r->err[0] && r->off != r->n) bad(r, "the end of the file", "trailing bytes", (long long)(r->n - r->off));
    return !r->err[0];
}

static void start_values(Model *m) {
    memset(m->u, 0, sizeof m->u);
    for (int k = 0; k < m->n_in; k++) m->u[k] = m->in_start[k];
    for (int k = 0; k < m->n_par; k++) {
        Param *p = &m->par[k];
        p->num = p->start;
        snprintf(p->str, STR_CAP, "%s", p->start_str);
    }
    m->t = m->wc = m->w_prev = 0.0;
    m->last_flags = 0;
    for (int k = 0; k < m->n_out; k++) m->out[k] = 0.0;
}

static int read_file(const char *path, unsigned char **buf, size_t *n, char *err, size_t errn) {
    FILE *f = fopen(path, "rb");
    if (!f) {
        snprintf(err, errn, "cannot open %s", path);
        return -1;
    }
    if (fseek(f, 0, SEEK_END) != 0) {
        fclose(f);
        snprintf(err, errn, "cannot read %s", path);
        return -1;
    }
    long len = ftell(f);
    if (len < 0 || len > (1L << 30)) {
        fclose(f);
        snprintf(err, errn, "cannot read %s (size %ld)", path, len);
        return -1;
    }
    rewind(f);
    *buf = (unsigned char *)malloc((size_t)len + 1);
    if (!*buf) {
        fclose(f);
        snprintf(err, errn, "out of memory reading %s", path);
        return -1;
    }
    size_t got = fread(*buf, 1, (size_t)len, f);
    fclose(f);
    if (got != (size_t)len) {
        free(*buf);
        snprintf(err, errn, "cannot read %s (%zu of %ld bytes)", path, got, len);
        return -1;
    }
    *n = (size_t)len;
    return 0;
}

void *model_new(Instance *c, const char *resource_dir, const char *guid) {
    char path[4200];
    snprintf(path, sizeof path, "%s/%s", resource_dir, TABLE_FILE);
    unsigned char *buf = NULL;
    size_t n = 0;
    char err[600];
    if (read_file(path, &buf, &n, err, sizeof err)) {
        fmu_log(c, fmi2Error, "fmi2Instantiate: the operating-map table: %s (the FMU's resources/%s; rebuild the FMU "
                "with bearing build-map-fmu)", err, TABLE_FILE);
        return NULL;
    }
    const char *why = NULL;
    char wbuf[256];
    if (n < TABLE_HEADER || memcmp(buf, TABLE_MAGIC, 8))
        why = "not an operating-map table (no BRGMAPTB header)";
    else if (le_get_u32(buf + 8) != TABLE_VERSION) {
        snprintf(wbuf, sizeof wbuf, "table of format version %u; this FMU reads version %u", le_get_u32(buf + 8),
                 (unsigned)TABLE_VERSION);
        why = wbuf;
    } else if (le_get_u32(buf + 12) != TABLE_HEADER || le_get_u32(buf + 28) != 0x01020304u)
        why = "corrupt table header";
    else if (le_get_u32(buf + 16) != n || le_get_u32(buf + 20) != 0) {
        snprintf(wbuf, sizeof wbuf, "table of %zu bytes, its header says %u: truncated or padded", n,
                 le_get_u32(buf + 16));
        why = wbuf;
    } else if (crc32_ieee(buf + TABLE_HEADER, n - TABLE_HEADER) != le_get_u32(buf + 24))
        why = "corrupt table (CRC-32 mismatch)";
    if (why) {
        fmu_log(c, fmi2Error, "fmi2Instantiate: %s: %s", path, why);
        free(buf);
        return NULL;
    }
    Model *m = (Model *)calloc(1, sizeof *m);
    if (!m) {
        free(buf);
        return NULL;
    }
    Rd r = {buf + TABLE_HEADER, n - TABLE_HEADER, 0, ""};
    int ok = parse_table(m, &r);
    free(buf);
    if (!ok) {
        fmu_log(c, fmi2Error, "fmi2Instantiate: %s: %s", path, r.err[0] ? r.err : "out of memory");
        model_delete(m);
        return NULL;
    }
    {   /* the ring variables of the directional derivative, by name */
        static const char *const reac[5] = {"reaction_Fx", "reaction_Fy", "reaction_Fz", "reaction_Mx", "reaction_My"};
        static const char *const ir[5] = {"ir_x", "ir_y", "ir_z", "ir_tx", "ir_ty"};
        static const char *const load[5] = {"Fx", "Fy", "Fz", "Mx", "My"};
        for (int i = 0; i < 5; i++) {
            m->o_reac[i] = m->o_ir[i] = m->i_load[i] = -1;
            for (int k = 0; k < m->n_out_real; k++) {
                if (!strcmp(m->out_names[k], reac[i])) m->o_reac[i] = k;
                if (!strcmp(m->out_names[k], ir[i])) m->o_ir[i] = k;
            }
            for (int k = 0; k < m->n_in; k++)
                if (!strcmp(m->in_names[k], load[i])) m->i_load[i] = k;
            if (m->o_reac[i] < 0 || m->o_ir[i] < 0 || m->i_load[i] < 0) {
                fmu_log(c, fmi2Error, "fmi2Instantiate: %s: corrupt table (no %s, %s or %s)", path, reac[i], ir[i],
                        load[i]);
                model_delete(m);
                return NULL;
            }
        }
    }
    if (guid && *guid && strcmp(guid, m->guid)) {
        fmu_log(c, fmi2Error, "fmi2Instantiate: GUID %s does not match this FMU's %s", guid, m->guid);
        model_delete(m);
        return NULL;
    }
    m->path = (char *)malloc(strlen(path) + 1);
    m->out = (double *)calloc((size_t)m->n_out, 8);
    m->new_out = (double *)calloc((size_t)m->n_out, 8);
    m->ss = (double *)calloc((size_t)m->n_vals, 8);
    if (!m->path || !m->out || !m->new_out || !m->ss) {
        model_delete(m);
        return NULL;
    }
    strcpy(m->path, path);
    start_values(m);
    return m;
}

void model_reset(void *mp) { start_values((Model *)mp); }
const char *model_guid(void *mp) { return ((Model *)mp)->guid; }
double model_time(void *mp) { return ((Model *)mp)->t; }

/* ---- variables: value references of modelDescription.xml (bearing_cosim/map_fmu.py) ---------------------- */
int model_var(void *mp, fmi2ValueReference vr, VarInfo *info) {
    Model *m = (Model *)mp;
    if (vr < (unsigned)m->n_in) {
        info->name = m->in_names[vr];
        info->type = VT_REAL;
        info->causality = VC_INPUT;
        return 1;
    }
    if (vr >= VR_OUTPUT && vr < VR_OUTPUT + (unsigned)m->n_out) {
        int k = (int)(vr - VR_OUTPUT);
        info->name = m->out_names[k];
        info->type = k < m->n_out_real ? VT_REAL : VT_INTEGER;
        info->causality = VC_OUTPUT;
        return 1;
    }
    if (vr >= VR_PARAMETER && vr < VR_PARAMETER + (unsigned)m->n_par) {
        Param *p = &m->par[vr - VR_PARAMETER];
        info->name = p->name;
        info->type = p->type;
        info->causality = VC_PARAMETER;
        return 1;
    }
    return 0;
}

double model_get_real(void *mp, fmi2ValueReference vr) {
    Model *m = (Model *)mp;
    if (vr < (unsigned)m->n_in) return m->u[vr];
    if (vr >= VR_PARAMETER) return m->par[vr - VR_PARAMETER].num;
    return m->out[vr - VR_OUTPUT];
}
int model_get_integer(void *mp, fmi2ValueReference vr) {
    Model *m = (Model *)mp;
    if (vr >= VR_PARAMETER) return (int)m->par[vr - VR_PARAMETER].num;
    return (int)m->out[vr - VR_OUTPUT]; /* as int() of the session's value */
}
int model_get_boolean(void *mp, fmi2ValueReference vr) { return ((Model *)mp)->par[vr - VR_PARAMETER].num != 0.0; }
const char *model_get_string(void *mp, fmi2ValueReference vr) { return ((Model *)mp)->par[vr - VR_PARAMETER].str; }

int model_set_real(void *mp, fmi2ValueReference vr, double v, char *err, size_t n) {
    Model *m = (Model *)mp;
    if (vr < (unsigned)m->n_in) {
        m->u[vr] = v; /* checked at the step, which names a non-finite input */
        return 0;
    }
    Param *p = &m->par[vr - VR_PARAMETER];
    if (!isfinite(v)) {
        char t[64];
        py_repr_double(v, t, sizeof t);
        snprintf(err, n, "%s = %s is outside the allowed range a finite number", p->name, t);
        return -1;
    }
    p->num = v;
    return 0;
}
int model_set_integer(void *mp, fmi2ValueReference vr, int v, char *err, size_t n) {
    (void)err, (void)n;
    ((Model *)mp)->par[vr - VR_PARAMETER].num = (double)v;
    return 0;
}
int model_set_boolean(void *mp, fmi2ValueReference vr, int v, char *err, size_t n) {
    (void)err, (void)n;
    ((Model *)mp)->par[vr - VR_PARAMETER].num = v ? 1.0 : 0.0;
    return 0;
}
int model_set_string(void *mp, fmi2ValueReference vr, const char *v, char *err, size_t n) {
    Param *p = &((Model *)mp)->par[vr - VR_PARAMETER];
    if (strlen(v) >= STR_CAP) {
        snprintf(err, n, "%s has %zu characters; allowed: at most %d", p->name, strlen(v), STR_CAP - 1);
        return -1;
    }
    snprintf(p->str, STR_CAP, "%s", v);
    return 0;
}

static void param_text(const Param *p, char *buf, size_t n) {
    if (p->type == VT_STRING)
        py_repr_string(p->str, buf, n);
    else if (p->type == VT_BOOLEAN)
        snprintf(buf, n, "%s", p->num != 0.0 ? "True" : "False");
    else if (p->type == VT_INTEGER)
        snprintf(buf, n, "%d", (int)p->num);
    else
        py_repr_double(p->num, buf, n);
}

void model_value_text(void *mp, fmi2ValueReference vr, char *buf, size_t n) {
    Model *m = (Model *)mp;
    if (vr < (unsigned)m->n_in)
        py_repr_double(m->u[vr], buf, n);
    else if (vr >= VR_PARAMETER)
        param_text(&m->par[vr - VR_PARAMETER], buf, n);
    else
        py_repr_double(m->out[vr - VR_OUTPUT], buf, n);
}

/* ---- the level (bearing_core.session.map_kernels, fidelity.MapLevel / SteadySession) ----------------------- */
static int str_ieq(const char *a, const char *b) {
    for (; *a && *b; a++, b++) {
        int x = (unsigned char)*a, y = (unsigned char)*b;
        if (x >= 'A' && x <= 'Z') x += 32;
        if (y >= 'A' && y <= 'Z') y += 32;
        if (x != y) return 0;
    }
    return *a == *b;
}

/* MapLevel._check_parameters and the oil temperature's axis (MapLevel.__init__): 0, or -1 with the message */
static int check_parameters(Model *m, char *err, size_t n) {
    char v[STR_CAP + 16];
    for (int pass = 0; pass < 3; pass++) /* fidelity and map_file, then the build parameters, then fixed ones */
        for (int k = 0; k < m->n_par; k++) {
            Param *p = &m->par[k];
            if (p->check == CHECK_NONE) continue; /* no effect at the map level */
            int want = p->check == CHECK_FIDELITY || p->check == CHECK_MAP_FILE || p->check == CHECK_ENUM
                           ? 0
                           : (p->check == CHECK_BUILT || p->check == CHECK_OIL_AXIS ? 1 : 2);
            if (want != pass) continue;
            param_text(p, v, sizeof v);
            if (p->check == CHECK_OIL_AXIS) {
                const Axis *a = &m->ax[m->i_axis_oil];
                double lo = m->axes[a->off] + 273.15, hi = m->axes[a->off + a->n - 1] + 273.15;
                if (!(lo - 1e-9 <= p->num && p->num <= hi + 1e-9)) {
                    snprintf(err, n, "oil_temperature = %s is invalid; allowed: %.6g K <= value <= %.6g K (the map's "
                             "range, %s; fidelity 'map' never extrapolates)", v, lo, hi, m->path);
                    return -1;
                }
                continue;
            }
            int same;
            if (p->type == VT_STRING) {
                same = p->check == CHECK_BUILT ? str_ieq(p->str, p->start_str) : !strcmp(p->str, p->start_str);
                for (int j = 0; j < p->n_alt && !same; j++) same = !strcmp(p->str, p->alt[j]);
            } else if (p->check == CHECK_BUILT && p->type != VT_BOOLEAN) {
                double b = p->start;
                same = fabs(p->num - b) <= 1e-9 * (fabs(b) > 1.0 ? fabs(b) : 1.0);
            } else {
                same = p->num == p->start;
            }
            if (same) continue;
            if (p->check == CHECK_BUILT)
                snprintf(err, n, "%s = %s is invalid; allowed: %s, the value the operating map %s was built for "
                         "(fidelity 'map' reads the map only for the parameters it was built with)", p->name, v,
                         p->repr, m->path);
            else if (p->check == CHECK_FIXED)
                snprintf(err, n, "%s = %s is invalid; allowed: %s at fidelity 'map' (%s)", p->name, v, p->repr,
                         p->detail);
            else if (p->check == CHECK_ENUM)
                snprintf(err, n, "%s = %s is invalid; allowed: %s, %s (this FMU holds one operating map)", p->name, v,
                         p->repr, p->detail);
            else
                snprintf(err, n, "%s = %s is invalid; allowed: %s (%s)", p->name, v, p->repr, p->detail);
            return -1;
        }
    return 0;
}

static const char *axis_unit(const char *name) {
    if (!strcmp(name, "my_Nm")) return "N.m";
    if (!strcmp(name, "oil_temperature_C")) return "degC";
    return "N";
}

/* MapLevel.range_error: the value xd of axis d outside the map */
static void range_error(Model *m, int d, double xd, char *err, size_t n) {
    const Axis *a = &m->ax[d];
    double lo = m->axes[a->off], hi = m->axes[a->off + a->n - 1];
    char v[64];
    if (!strcmp(a->name, "speed_rpm")) {
        py_repr_double(xd * m->rpm, v, sizeof v);
        snprintf(err, n, "shaft_speed = %s is invalid; allowed: %.6g rad/s <= value <= %.6g rad/s (%.6g-%.6g rpm), the "
                 "range of the operating map %s (fidelity 'map' never extrapolates)", v, lo * m->rpm, hi * m->rpm, lo,
                 hi, m->path);
        return;
    }
    py_repr_double(xd, v, sizeof v);
    if (!strcmp(a->name, "fx_N") && m->rotate) {
        snprintf(err, n, "radial load hypot(Fx, Fy) = %s is invalid; allowed: %.6g N <= value <= %.6g N, the range "
                 "of the operating map %s (fidelity 'map' never extrapolates)", v, lo, hi, m->path);
        return;
    }
    const char *unit = axis_unit(a->name);
    const char *name = a->kind == 0 ? "oil_temperature" : m->in_names[a->kind == 3 ? a->input : (a->kind == 1 ? m->i_speed : m->i_fx)];
    snprintf(err, n, "%s = %s is invalid; allowed: %.6g %s <= value <= %.6g %s, the range of the operating map %s "
             "(fidelity 'map' never extrapolates)", name, v, lo, unit, hi, unit, m->path);
}

/* parse_inputs and MapLevel.query: the map coordinates x of the inputs u and the radial load's direction (cs, sn);
   0, or -1 with the message of the first refused input */
static int query(Model *m, const double *u, double *x, double *cs, double *sn, char *err, size_t n) {
    char v[64];
    for (int k = 0; k < m->n_in; k++)
        if (!isfinite(u[k])) {
            py_repr_double(u[k], v, sizeof v);
            snprintf(err, n, "%s = %s is invalid; allowed: a finite number", m->in_names[k], v);
            return -1;
        }
    if (u[m->i_oring] != 0.0) {
        py_repr_double(u[m->i_oring], v, sizeof v);
        snprintf(err, n, "outer_ring_speed = %s is invalid; allowed: 0 rad/s at fidelity 'map' (the map is of the "
                 "bearing with the outer ring fixed)", v);
        return -1;
    }
    *cs = 1.0;
    *sn = 0.0;
    double fx = u[m->i_fx];
    if (m->rotate) {
        double fr = sqrt(u[m->i_fx] * u[m->i_fx] + u[m->i_fy] * u[m->i_fy]); /* as map_kernels.map_step */
        if (fr > 0.0) {
            *cs = u[m->i_fx] / fr;
            *sn = u[m->i_fy] / fr;
        }
        fx = fr;
    }
    for (int k = 0; k < m->n_zero; k++) {
        int i = m->zero_in[k];
        if (u[i] != 0.0) {
            const char *name = m->in_names[i];
            const char *unit = name[0] == 'F' ? "N" : "N.m";
            const char *axis = !strcmp(name, "Fy") ? "fy_N" : (!strcmp(name, "My") ? "my_Nm" : name);
            py_repr_double(u[i], v, sizeof v);
            snprintf(err, n, "%s = %s is invalid; allowed: 0 %s at fidelity 'map' (the map %s has no %s axis)", name, v,
                     unit, m->path, axis);
            return -1;
        }
    }
    for (int d = 0; d < m->n_axes; d++) {
        const Axis *a = &m->ax[d];
        double val;
        if (a->kind == 0)
            val = a->fixed;
        else if (a->kind == 1)
            val = u[m->i_speed] / m->rpm;
        else if (a->kind == 2)
            val = fx;
        else
            val = u[a->input];
        if (!(a->lo - a->tol <= val && val <= a->hi + a->tol)) {
            range_error(m, d, val, err, n);
            return -1;
        }
        x[d] = val < a->lo ? a->lo : (val > a->hi ? a->hi : val);
    }
    return 0;
}

/* map_kernels.interp_multilinear: the nv values per grid point of values at x into out (those flagged in
   speed_scaled times x[0]); returns the cell's validity flags (flags NULL: 0) */
static int interp_multilinear(Model *m, const double *x, const double *values, int nv, const int *speed_scaled,
                              const int *flags, double *out) {
    int nd = m->n_axes;
    for (int d = 0; d < nd; d++) {
        const Axis *a = &m->ax[d];
        const double *ax = m->axes + a->off;
        if (a->n == 1) {
            m->idx[d] = 0;
            m->w[d] = 0.0;
            continue;
        }
        int lo = 0, hi = a->n - 1;
        while (hi - lo > 1) { /* bisection: at most log2(n) halvings */
            int mid = (lo + hi) / 2;
            if (ax[mid] <= x[d])
                lo = mid;
            else
                hi = mid;
        }
        m->idx[d] = lo;
        m->w[d] = (x[d] - ax[lo]) / (ax[lo + 1] - ax[lo]);
    }
    for (int k = 0; k < nv; k++) out[k] = 0.0;
    int fl = 0;
    for (int cnr = 0; cnr < (1 << nd); cnr++) {
        double wt = 1.0;
        long long off = 0;
        for (int d = 0; d < nd; d++) {
            if ((cnr >> d) & 1) {
                wt *= m->w[d];
                off += (long long)(m->idx[d] + 1) * m->strides[d];
            } else {
                wt *= 1.0 - m->w[d];
                off += (long long)m->idx[d] * m->strides[d];
            }
            if (wt == 0.0) break;
        }
        if (wt == 0.0) continue;
        if (flags) fl |= flags[off];
        const double *row = values + off * nv;
        for (int k = 0; k < nv; k++) out[k] += wt * row[k];
    }
    if (speed_scaled)
        for (int k = 0; k < nv; k++)
            if (speed_scaled[k] != 0) out[k] *= x[0];
    return fl;
}

/* map_kernels.steady_level_outputs: the outputs of a communication point into m->new_out; returns the cage speed
   at the end of the step, NaN if an output is not finite */
static double steady_level_outputs(Model *m, double cs, double sn, double wc0, double h, double tau, double shaft,
                                   double shaft0) {
    const double *ss = m->ss;
    double *out = m->new_out;
    const int *ib = m->ib;
    int n = m->n_out;
    for (int i = 0; i < n; i++) out[i] = m->src[i] >= 0 ? ss[m->src[i]] : 0.0;
    for (int r = 0; r < m->n_rot; r++) {
        int i = m->rot[2 * r], j = m->rot[2 * r + 1];
        double a = out[i], b = out[j];
        out[i] = cs * a - sn * b;
        out[j] = sn * a + cs * b;
    }
    double wss = out[ib[0]];
    double wc = wss;
    if (h > 0.0 && tau > 0.0) wc = wss + (wc0 - wss) * exp(-h / tau);
    out[ib[0]] = wc;
    double csr = 0.0, csr_t = 0.0;
    if (fabs(shaft) >= m->csr_min) {
        csr = wc / shaft;
        csr_t = ss[ib[6]] / shaft;
    }
    out[ib[1]] = csr;
    out[ib[2]] = csr_t;
    out[ib[3]] = csr_t > 0.0 ? 1.0 - csr / csr_t : 0.0;
    double w_outer = out[ib[7]];
    double s = 0.0, state = 0.0;
    if (fabs(w_outer) >= m->skid_min) {
        s = (w_outer - wc) / w_outer;
        if (s > m->skid_tol)
            state = 1.0;
        else if (s < -m->skid_tol)
            state = -1.0;
    }
    out[ib[4]] = s;
    out[ib[5]] = state;
    for (int k = 0; k < N_TEMPS; k++) out[ib[8 + k]] = m->temps[k];
    if (m->inertia > 0.0 && h > 0.0 && fabs(shaft) >= m->csr_min) {
        double c = wss / shaft;
        double p_acc = 0.5 * m->inertia * c * c * (shaft * shaft - shaft0 * shaft0) / h;
        for (int k = 0; k < 2; k++) {
            out[ib[10 + N_TEMPS + k]] += p_acc;
            out[ib[8 + N_TEMPS + k]] += p_acc / shaft;
        }
    }
    for (int i = 0; i < n; i++)
        if (!isfinite(out[i])) return NAN;
    return wc;
}

/* map_kernels.map_stiffness: the map's stiffness K0 interpolated at x (the outputs' cell and weights), turned
   with the radial load's direction, K = R K0 R^T with R = diag(Rz, 1, Rz), Rz = [[cs, -sn], [sn, cs]] on the
   (x, y) and (tx, ty) pairs: columns first, then rows; into new_out[i_k:i_k + 25]. 0 if an entry is not finite. */
static int map_stiffness(Model *m, const double *x, double cs, double sn) {
    double *k = m->kbuf;
    interp_multilinear(m, x, m->kvals, 25, NULL, NULL, k);
    for (int i = 0; i < 5; i++)
        for (int p = 0; p <= 3; p += 3) {
            double a = k[5 * i + p], b = k[5 * i + p + 1];
            k[5 * i + p] = cs * a - sn * b;
            k[5 * i + p + 1] = sn * a + cs * b;
        }
    for (int j = 0; j < 5; j++)
        for (int p = 0; p <= 3; p += 3) {
            double a = k[5 * p + j], b = k[5 * (p + 1) + j];
            k[5 * p + j] = cs * a - sn * b;
            k[5 * (p + 1) + j] = sn * a + cs * b;
        }
    for (int q = 0; q < 25; q++)
        if (!isfinite(k[q])) return 0;
    for (int q = 0; q < 25; q++) m->new_out[m->i_k + q] = k[q];
    return 1;
}

/* MapLevel.point_text */
static void point_text(Model *m, const double *x, char *buf, size_t n) {
    size_t k = 0;
    buf[0] = 0;
    for (int d = 0; d < m->n_axes && k < n; d++)
        k += (size_t)snprintf(buf + k, n - k, "%s%s %.5g", d ? ", " : "", m->ax[d].name, x[d]);
}

/* SteadySession._note_flags: a warning when the point enters a cell with other validity flags */
static int note_flags(Instance *c, Model *m, int fl, const double *x, double h) {
    int warned = 0;
    if (fl && fl != m->last_flags) {
        char pt[600], what[1200] = "";
        point_text(m, x, pt, sizeof pt);
        if (fl & FLAG_GROSS_SKID) snprintf(what, sizeof what, "%s", m->flag_text[0]);
        if (fl & FLAG_CAGE_UNSTEADY) {
            size_t k = strlen(what);
            snprintf(what + k, sizeof what - k, "%s%s", k ? " and " : "", m->flag_text[1]);
        }
        char msg[sizeof m->pending];
        snprintf(msg, sizeof msg, "t = %.6g s: the operating point (%s) entered a region of %s, where fidelity 'map' "
                 "is least accurate (docs/fidelity.md); use fidelity 'dynamic' for this operation", m->t + h, pt, what);
        if (m->defer)
            memcpy(m->pending, msg, sizeof msg);
        else
            fmu_log(c, fmi2Warning, "%s", msg);
        warned = 1;
    }
    m->last_flags = fl;
    return warned;
}

/* map_kernels.map_fatigue (SteadySession._life_into, map level): life_L10r_h [h] and fatigue_damage [-] into
   new_out at the end of a step of h [s] (h = 0: the start, damage 0), the damage so far in out (the model's
   state). With the interpolated damage
   rate r = ss[i_rate] [1/s] (the map's fatigue_damage_rate, per unit speed times the speed):
       life_L10r_h = min(1 / (3600 r), life_cap) if r > 0 else life_cap
       fatigue_damage = fatigue_damage + r h      if r > 0 (else unchanged)
   A map without the rate (i_rate -1): both 0 (life unknown). */
static void life_into(Model *m, double h) {
    double d = h > 0.0 ? m->out[m->i_damage] : 0.0;
    if (m->i_rate >= 0) {
        double r = m->ss[m->i_rate];
        if (r > 0.0) {
            double L = 1.0 / (3600.0 * r);
            m->new_out[m->i_life] = L < m->life_cap ? L : m->life_cap;
            d = d + r * h;
        } else {
            m->new_out[m->i_life] = m->life_cap;
        }
    } else {
        m->new_out[m->i_life] = 0.0;
        d = 0.0;
    }
    m->new_out[m->i_damage] = d;
}

/* SteadySession._evaluate: the outputs at the inputs into new_out; the cage speed, or NaN with the message */
static double evaluate(Instance *c, Model *m, double h, int *warned, char *err, size_t n) {
    double cs, sn;
    double *x = m->x;
    if (query(m, m->u, x, &cs, &sn, err, n)) return NAN;
    int fl = interp_multilinear(m, x, m->values, m->n_vals, m->speed_scaled, m->flags, m->ss);
    double w = m->u[m->i_speed];
    double tau = m->ss[m->i_tau];
    double wc = steady_level_outputs(m, cs, sn, m->wc, h, tau, w, h > 0.0 ? m->w_prev : w);
    if (!isfinite(wc)) {
        char pt[600], names[400] = "[";
        point_text(m, x, pt, sizeof pt);
        int nb = 0;
        for (int i = 0; i < m->n_out && nb < 4; i++)
            if (!isfinite(m->new_out[i])) {
                size_t k = strlen(names);
                snprintf(names + k, sizeof names - k, "%s'%s'", nb ? ", " : "", m->out_names[i]);
                nb++;
            }
        strcat(names, "]");
        snprintf(err, n, "inputs = '%s' is invalid; allowed: an operating point where the map has values (operating map "
                 "%s (%s level, %s) has no value for %s there (a failed grid point))", pt, m->path, m->level,
                 m->bearing, names);
        return NAN;
    }
    if (m->has_k && !map_stiffness(m, x, cs, sn)) {
        char pt[600];
        point_text(m, x, pt, sizeof pt);
        snprintf(err, n, "inputs = '%s' is invalid; allowed: an operating point where the map has values (operating map "
                 "%s (%s level, %s) has no finite stiffness there (a failed grid point))", pt, m->path, m->level,
                 m->bearing);
        return NAN;
    }
    *warned = note_flags(c, m, fl, x, h);
    if (m->i_oil >= 0) m->new_out[m->i_oil] = m->oil_fraction;
    life_into(m, h);
    return wc;
}

int model_initialize(Instance *c, void *mp, double t0, char *err, size_t n) {
    Model *m = (Model *)mp;
    if (check_parameters(m, err, n)) return fmi2Error;
    for (int k = 0; k < m->n_par; k++) /* the isothermal temperatures: the oil_temperature parameter [K] */
        if (!strcmp(m->par[k].name, "oil_temperature")) {
            for (int j = 0; j < 4; j++) m->temps[j] = m->par[k].num;
            if (m->i_axis_oil >= 0) m->ax[m->i_axis_oil].fixed = m->par[k].num - 273.15;
        }
    m->t = 0.0;
    m->wc = 0.0;
    m->w_prev = 0.0;
    m->last_flags = 0;
    int warned = 0;
    m->defer = 1; /* SteadySession: the level's warnings of its construction first, then the flags' */
    m->pending[0] = 0;
    double wc = evaluate(c, m, 0.0, &warned, err, n);
    m->defer = 0;
    if (!isfinite(wc)) return fmi2Error;
    const char *missing[2] = {m->stiffness_missing, m->fatigue_missing};
    for (int k = 0; k < 2; k++)
        if (missing[k][0]) { /* the table writes the map's file as {map}: this FMU's own table */
            const char *at = strstr(missing[k], "{map}");
            if (at)
                fmu_log(c, fmi2Warning, "%.*s%s%s", (int)(at - missing[k]), missing[k], m->path, at + 5);
            else
                fmu_log(c, fmi2Warning, "%s", missing[k]);
            warned = 1;
        }
    if (m->pending[0]) fmu_log(c, fmi2Warning, "%s", m->pending);
    m->wc = wc;
    m->w_prev = m->u[m->i_speed];
    memcpy(m->out, m->new_out, (size_t)m->n_out * 8);
    m->t = t0;
    return warned ? fmi2Warning : fmi2OK;
}

int model_step(Instance *c, void *mp, double t, double h, char *err, size_t n) {
    Model *m = (Model *)mp;
    char a[64], b[64];
    if (!(isfinite(h) && h > 0.0)) {
        py_repr_double(h, a, sizeof a);
        snprintf(err, n, "communication step h = %s is invalid; allowed: h > 0", a);
        return fmi2Discard;
    }
    if (fabs(t - m->t) > 1e-9 * (fabs(t) > 1.0 ? fabs(t) : 1.0) || !isfinite(t)) {
        py_repr_double(t, a, sizeof a);
        py_repr_double(m->t, b, sizeof b);
        snprintf(err, n, "step starts at t = %s but the bearing is at t = %s", a, b);
        return fmi2Discard;
    }
    int warned = 0;
    int flags0 = m->last_flags;
    double wc = evaluate(c, m, h, &warned, err, n);
    if (!isfinite(wc)) {
        m->last_flags = flags0;
        return fmi2Discard;
    }
    m->w_prev = m->u[m->i_speed];
    m->wc = wc;
    memcpy(m->out, m->new_out, (size_t)m->n_out * 8);
    m->t = t + h;
    return warned ? fmi2Warning : fmi2OK;
}

/* ---- FMU state: version, counts, t, wc, w_prev, flags, inputs, outputs, parameters (little-endian) ----------
   The outputs include fatigue_damage, the Palmgren-Miner sum of the run (life_into adds to it): the state carries it. */
size_t model_state_size(void *mp) {
    Model *m = (Model *)mp;
    return 16 + 24 + 4 + 8 * (size_t)m->n_in + 8 * (size_t)m->n_out + (size_t)m->n_par * (8 + STR_CAP);
}

void model_state_save(void *mp, unsigned char *p) {
    Model *m = (Model *)mp;
    le_put_u32(p, STATE_VERSION);
    le_put_u32(p + 4, (unsigned)m->n_in);
    le_put_u32(p + 8, (unsigned)m->n_out);
    le_put_u32(p + 12, (unsigned)m->n_par);
    le_put_f64(p + 16, m->t);
    le_put_f64(p + 24, m->wc);
    le_put_f64(p + 32, m->w_prev);
    le_put_u32(p + 40, (unsigned)m->last_flags);
    p += 44;
    for (int k = 0; k < m->n_in; k++, p += 8) le_put_f64(p, m->u[k]);
    for (int k = 0; k < m->n_out; k++, p += 8) le_put_f64(p, m->out[k]);
    for (int k = 0; k < m->n_par; k++) {
        le_put_f64(p, m->par[k].num);
        memset(p + 8, 0, STR_CAP);
        memcpy(p + 8, m->par[k].str, strlen(m->par[k].str));
        p += 8 + STR_CAP;
    }
}

int model_state_load(void *mp, const unsigned char *p, size_t size, char *err, size_t n) {
    Model *m = (Model *)mp;
    if (size != model_state_size(m)) {
        snprintf(err, n, "state of %zu bytes; this FMU's states have %zu", size, model_state_size(m));
        return -1;
    }
    if (le_get_u32(p) != STATE_VERSION || le_get_u32(p + 4) != (unsigned)m->n_in ||
        le_get_u32(p + 8) != (unsigned)m->n_out || le_get_u32(p + 12) != (unsigned)m->n_par) {
        snprintf(err, n, "state of another version or model (version %u, %u inputs, %u outputs, %u parameters)",
                 le_get_u32(p), le_get_u32(p + 4), le_get_u32(p + 8), le_get_u32(p + 12));
        return -1;
    }
    double t = le_get_f64(p + 16), wc = le_get_f64(p + 24), wp = le_get_f64(p + 32);
    unsigned fl = le_get_u32(p + 40);
    if (!isfinite(t) || !isfinite(wc) || !isfinite(wp) || fl > 3) {
        snprintf(err, n, "corrupt state (time, cage speed, shaft speed or flags not valid)");
        return -1;
    }
    const unsigned char *q = p + 44 + 8 * (size_t)m->n_in;
    for (int k = 0; k < m->n_out; k++)
        if (!isfinite(le_get_f64(q + 8 * k))) {
            snprintf(err, n, "corrupt state (output %s is not finite)", m->out_names[k]);
            return -1;
        }
    q += 8 * (size_t)m->n_out;
    for (int k = 0; k < m->n_par; k++) {
        const unsigned char *s = q + (size_t)k * (8 + STR_CAP);
        const Param *pr = &m->par[k];
        double v = le_get_f64(s);
        if (!isfinite(v) || (pr->type == VT_BOOLEAN && v != 0.0 && v != 1.0) || memchr(s + 8, 0, STR_CAP) == NULL) {
            snprintf(err, n, "corrupt state (parameter %s)", pr->name);
            return -1;
        }
    }
    m->t = t;
    m->wc = wc;
    m->w_prev = wp;
    m->last_flags = (int)fl;
    const unsigned char *r = p + 44;
    for (int k = 0; k < m->n_in; k++, r += 8) m->u[k] = le_get_f64(r);
    for (int k = 0; k < m->n_out; k++, r += 8) m->out[k] = le_get_f64(r);
    for (int k = 0; k < m->n_par; k++, r += 8 + STR_CAP) {
        m->par[k].num = le_get_f64(r);
        memcpy(m->par[k].str, r + 8, STR_CAP);
    }
    return 0;
}

/* ---- directional derivatives (load coupling): from the stiffness outputs of the last communication point ----
 * K = d(load)/d(pose) (outputs stiffness[i,j]; rows Fx..My, columns dx..ty). With the loads Fx..My the inputs:
 *   d ir_i / d load_j = (K^-1)[i][j] (the compliance, over the pose's free coordinates: a coordinate whose row and
 *   column of K are zero has zero compliance), d reaction_i / d load_j = -delta_ij (the steady balance
 *   reaction = -load); every other pair 0. As BearingFMU's fmi2GetDirectionalDerivative at fidelity = map. */

/* C = K^-1 over the free coordinates by Gauss-Jordan elimination with partial pivoting; 0 if K is zero or singular
   (a pivot below 1e-12 of K's largest entry) */
static int compliance(const double K[25], double C[25]) {
    int free_[5], n = 0;
    double kmax = 0.0;
    for (int i = 0; i < 5; i++) {
        int used = 0;
        for (int j = 0; j < 5; j++) {
            used |= K[5 * i + j] != 0.0 || K[5 * j + i] != 0.0;
            kmax = fabs(K[5 * i + j]) > kmax ? fabs(K[5 * i + j]) : kmax;
        }
        if (used) free_[n++] = i;
    }
    for (int q = 0; q < 25; q++) C[q] = 0.0;
    if (n == 0) return 0;
    double aug[5][10];
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++) {
            aug[i][j] = K[5 * free_[i] + free_[j]];
            aug[i][n + j] = (i == j) ? 1.0 : 0.0;
        }
    for (int col = 0; col < n; col++) {
        int best = col;
        for (int r = col + 1; r < n; r++)
            if (fabs(aug[r][col]) > fabs(aug[best][col])) best = r;
        if (!(fabs(aug[best][col]) > 1e-12 * kmax)) return 0;
        for (int j = 0; j < 2 * n && best != col; j++) {
            double t = aug[col][j];
            aug[col][j] = aug[best][j];
            aug[best][j] = t;
        }
        double pivot = aug[col][col];
        for (int j = 0; j < 2 * n; j++) aug[col][j] /= pivot;
        for (int r = 0; r < n; r++)
            if (r != col && aug[r][col] != 0.0) {
                double f = aug[r][col];
                for (int j = 0; j < 2 * n; j++) aug[r][j] -= f * aug[col][j];
            }
    }
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++) C[5 * free_[i] + free_[j]] = aug[i][n + j];
    return 1;
}

static int slot(const int ix[5], int k) {
    for (int i = 0; i < 5; i++)
        if (ix[i] == k) return i;
    return -1;
}

int model_directional_derivative(void *mp, const fmi2ValueReference *z, size_t nz, const fmi2ValueReference *u,
                                 size_t nu, const double *dv, double *df, char *err, size_t n) {
    Model *m = (Model *)mp;
    double K[25], C[25];
    int any = 0, need_c = 0;
    for (int q = 0; q < 25; q++) {
        K[q] = m->has_k ? m->out[m->i_k + q] : 0.0;
        any |= K[q] != 0.0;
    }
    for (size_t a = 0; a < nz; a++) need_c |= slot(m->o_ir, (int)(z[a] - VR_OUTPUT)) >= 0;
    if (need_c && !compliance(K, C)) {
        snprintf(err, n, "the stiffness of the last communication point is %s, so the compliance d ir/d load (its "
                 "inverse) does not exist%s", any ? "singular" : "zero",
                 any ? "" : " (fidelity map with an operating map without stiffness variables: rebuild it with "
                            "bearing build-map)");
        return -1;
    }
    for (size_t a = 0; a < nz; a++) {
        int oz = (int)(z[a] - VR_OUTPUT);
        int ir = slot(m->o_ir, oz), re = slot(m->o_reac, oz);
        double acc = 0.0;
        for (size_t b = 0; b < nu; b++) {
            int jl = slot(m->i_load, (int)u[b]);
            double d = 0.0;
            if (jl >= 0 && ir >= 0)
                d = C[5 * ir + jl];
            else if (jl >= 0 && re >= 0)
                d = re == jl ? -1.0 : 0.0;
            acc += d * dv[b];
        }
        df[a] = acc;
    }
    return 0;
}
