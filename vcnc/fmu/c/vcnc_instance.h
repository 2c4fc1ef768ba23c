/* One running axis model as the FMI layers see it: life-cycle phases, variable access by value
 * reference, communication steps. Shared by fmi2_layer.c and fmi3_layer.c, which only translate
 * the calling conventions of their standard.
 */
#ifndef VCNC_INSTANCE_H
#define VCNC_INSTANCE_H

#include <stddef.h>

#include "vcnc_model.h"

typedef enum { VCNC_OK = 0, VCNC_WARNING = 1, VCNC_DISCARD = 2, VCNC_ERROR = 3, VCNC_FATAL = 4 } vcnc_status;

typedef enum {
    VCNC_INSTANTIATED = 0,
    VCNC_INITIALIZATION = 1,
    VCNC_STEPPING = 2,
    VCNC_TERMINATED = 3
} vcnc_phase;

struct vcnc_instance;

/* any function pointer; the FMI layer casts it back to its logger type */
typedef void (*vcnc_callback)(void);
typedef void (*vcnc_log_fn)(const struct vcnc_instance *inst, vcnc_status status, const char *category,
                            const char *message);

/* What an FMU state snapshot holds (fmi2GetFMUstate / fmi3GetFMUState). */
typedef struct {
    vcnc_model model;
    vcnc_phase phase;
    int dirty;               /* parameters or inputs changed since the last initialisation */
    double start_time;       /* [s] */
    long long steps;         /* samples since start_time */
} vcnc_snapshot;

typedef struct vcnc_instance {
    vcnc_snapshot s;
    int logging_on;
    char name[256];
    vcnc_log_fn log;         /* set by the FMI layer */
    void *env;               /* the FMI layer's environment pointer */
    vcnc_callback callback;  /* the FMI layer's logger function */
} vcnc_instance;

/* The token (FMI 2 GUID / FMI 3 instantiationToken) this binary was built for. */
extern const char vcnc_token[];

vcnc_instance *vcnc_instance_new(const char *name, const char *token, int logging_on, vcnc_log_fn log, void *env,
                                 vcnc_callback callback);
void vcnc_instance_free(vcnc_instance *inst);
void vcnc_instance_reset(vcnc_instance *inst);

void vcnc_logf(const vcnc_instance *inst, vcnc_status status, const char *category, const char *fmt, ...);

vcnc_status vcnc_enter_initialization(vcnc_instance *inst, double start_time);
vcnc_status vcnc_exit_initialization(vcnc_instance *inst);
vcnc_status vcnc_terminate(vcnc_instance *inst);

vcnc_status vcnc_get_float(vcnc_instance *inst, const unsigned int vr[], size_t n, double values[]);
vcnc_status vcnc_set_float(vcnc_instance *inst, const unsigned int vr[], size_t n, const double values[]);
vcnc_status vcnc_get_int(vcnc_instance *inst, const unsigned int vr[], size_t n, int values[]);
vcnc_status vcnc_set_int(vcnc_instance *inst, const unsigned int vr[], size_t n, const int values[]);

/* Advance from current_time by step_size, which must be a whole number of sample times. */
vcnc_status vcnc_do_step(vcnc_instance *inst, double current_time, double step_size);
double vcnc_time(const vcnc_instance *inst);

vcnc_status vcnc_unsupported(const vcnc_instance *inst, const char *function);

#endif
