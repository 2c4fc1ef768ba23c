/* Life cycle and variable access of one axis model instance (see vcnc_instance.h). */
#include "vcnc_instance.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vcnc_config.h"

const char vcnc_token[] = VCNC_TOKEN;

void vcnc_logf(const vcnc_instance *inst, vcnc_status status, const char *category, const char *fmt, ...)
{
    char message[512];
    va_list ap;
    size_t i;
    if (!inst || !inst->log) return;
    if (status < VCNC_WARNING && !inst->logging_on) return;
    va_start(ap, fmt);
    vsnprintf(message, sizeof(message), fmt, ap);
    va_end(ap);
    /* the FMI 2 logger treats its message as a printf format */
    for (i = 0; message[i]; i++) {
        if (message[i] == '%') message[i] = ' ';
    }
    inst->log(inst, status, category, message);
}

static void set_defaults(vcnc_instance *inst)
{
    vcnc_parameters *p = &inst->s.model.par;
    static const double pp_coef[] = VCNC_START_PP_COEF, tp_coef[] = VCNC_START_TP_COEF;
    int i;
    memset(&inst->s, 0, sizeof(inst->s));
    p->a1 = VCNC_START_A1;
    p->a2 = VCNC_START_A2;
    p->a3 = VCNC_START_A3;
    p->b0 = VCNC_START_B0;
    p->b1 = VCNC_START_B1;
    p->b2 = VCNC_START_B2;
    p->d0 = VCNC_START_D0;
    p->d1 = VCNC_START_D1;
    p->sample_time = VCNC_START_SAMPLE_TIME;
    p->stribeck[0] = VCNC_START_STRIBECK_VELOCITY;
    p->stribeck[1] = VCNC_START_STRIBECK_EXCESS_POSITIVE;
    p->stribeck[2] = VCNC_START_STRIBECK_EXCESS_NEGATIVE;
    p->asym = VCNC_START_VISCOUS_ASYMMETRY;
    p->pp_period = VCNC_START_POSITION_PERIOD;
    p->pp_harmonics = VCNC_PP_HARMONICS;
    for (i = 0; i < 2 * VCNC_PP_HARMONICS; i++) p->pp_coef[i] = pp_coef[i];
    p->tp_on = VCNC_TP_ON;
    p->tp_period = VCNC_START_TIME_PERIOD;
    p->tp_mean = VCNC_START_TIME_MEAN;
    p->tp_harmonics = VCNC_TP_HARMONICS;
    for (i = 0; i < 2 * VCNC_TP_HARMONICS; i++) p->tp_coef[i] = tp_coef[i];
    p->drift = VCNC_START_DRIFT_RATE;
    p->ref_delay_s = VCNC_START_REFERENCE_DELAY_S;
    p->filter_s = VCNC_START_SETPOINT_FILTER_S;
    p->structured = VCNC_STRUCTURED;
    p->viscous_rate = VCNC_START_PLANT_VISCOUS_RATE;
    p->delay = VCNC_START_DELAY_SAMPLES;
    p->saturation = VCNC_START_SATURATION_LIMIT;
    p->anti_windup = VCNC_SAT_ANTI_WINDUP;
    p->integral_lead = VCNC_SAT_INTEGRAL_LEAD;
    p->backlash = VCNC_START_BACKLASH_WIDTH;
    p->res[0] = VCNC_START_RESONANCE_FREQUENCY;
    p->res[1] = VCNC_START_RESONANCE_DAMPING;
    p->res[2] = VCNC_START_RESONANCE_TABLE_FRACTION;
    p->res[3] = VCNC_RES_TABLE;
    inst->s.model.x_ref = VCNC_START_X_REF;
    inst->s.model.w_ext = VCNC_START_W_EXT;
    inst->s.phase = VCNC_INSTANTIATED;
    inst->s.dirty = 1;
}

vcnc_instance *vcnc_instance_new(const char *name, const char *token, int logging_on, vcnc_log_fn log, void *env,
                                 vcnc_callback callback)
{
    vcnc_instance *inst = (vcnc_instance *)calloc(1, sizeof(vcnc_instance));
    if (!inst) return NULL;
    strncpy(inst->name, name ? name : "", sizeof(inst->name) - 1);
    inst->logging_on = logging_on;
    inst->log = log;
    inst->env = env;
    inst->callback = callback;
    if (!token || strcmp(token, vcnc_token) != 0) {
        vcnc_logf(inst, VCNC_ERROR, "logStatusError",
                  "token %s does not match this binary (%s): the modelDescription.xml and the binary differ",
                  token ? token : "(null)", vcnc_token);
        free(inst);
        return NULL;
    }
    set_defaults(inst);
    return inst;
}

void vcnc_instance_free(vcnc_instance *inst)
{
    free(inst);
}

void vcnc_instance_reset(vcnc_instance *inst)
{
    set_defaults(inst);
}

double vcnc_time(const vcnc_instance *inst)
{
    return inst->s.start_time + (double)inst->s.steps * inst->s.model.par.sample_time;
}

vcnc_status vcnc_unsupported(const vcnc_instance *inst, const char *function)
{
    vcnc_logf(inst, VCNC_ERROR, "logStatusError", "%s is not supported by this FMU", function);
    return VCNC_ERROR;
}

/* (Re)compute the discretisation and the rest state while parameters may still change. */
static vcnc_status ensure_initialized(vcnc_instance *inst)
{
    char msg[256];
    if (!inst->s.dirty) return VCNC_OK;
    if (vcnc_model_initialize(&inst->s.model, msg, sizeof(msg)) != 0) {
        vcnc_logf(inst, VCNC_ERROR, "logStatusError", "cannot initialise the axis model: %s", msg);
        return VCNC_ERROR;
    }
    inst->s.dirty = 0;
    return VCNC_OK;
}

vcnc_status vcnc_enter_initialization(vcnc_instance *inst, double start_time)
{
    if (inst->s.phase != VCNC_INSTANTIATED) {
        vcnc_logf(inst, VCNC_ERROR, "logStatusError", "initialisation mode can only be entered once after instantiation");
        return VCNC_ERROR;
    }
    inst->s.phase = VCNC_INITIALIZATION;
    inst->s.start_time = start_time;
    inst->s.steps = 0;
    return VCNC_OK;
}

vcnc_status vcnc_exit_initialization(vcnc_instance *inst)
{
    vcnc_status status;
    if (inst->s.phase != VCNC_INITIALIZATION) {
        vcnc_logf(inst, VCNC_ERROR, "logStatusError", "not in initialisation mode");
        return VCNC_ERROR;
    }
    inst->s.dirty = 1;
    status = ensure_initialized(inst);
    if (status != VCNC_OK) return status;
    inst->s.phase = VCNC_STEPPING;
    vcnc_logf(inst, VCNC_OK, "logEvents", "initialised at rest at x_ref = %.17g mm, sample time %.17g s",
              inst->s.model.x_ref, inst->s.model.par.sample_time);
    return VCNC_OK;
}

vcnc_status vcnc_terminate(vcnc_instance *inst)
{
    inst->s.phase = VCNC_TERMINATED;
    return VCNC_OK;
}

#define SLOT(NAME, field) case VCNC_VR_##NAME: return VCNC_HAS_##NAME ? (field) : NULL

static double *parameter_slot(vcnc_instance *inst, unsigned int vr)
{
    vcnc_parameters *p = &inst->s.model.par;
    if (vr >= VCNC_VR_PP_COEF0 && vr < VCNC_VR_PP_COEF0 + 2u * VCNC_PP_HARMONICS) return &p->pp_coef[vr - VCNC_VR_PP_COEF0];
    if (vr >= VCNC_VR_TP_COEF0 && vr < VCNC_VR_TP_COEF0 + 2u * VCNC_TP_HARMONICS) return &p->tp_coef[vr - VCNC_VR_TP_COEF0];
    switch (vr) {
    case VCNC_VR_A1: return &p->a1;
    case VCNC_VR_A2: return &p->a2;
    case VCNC_VR_A3: return &p->a3;
    case VCNC_VR_B0: return &p->b0;
    case VCNC_VR_B1: return &p->b1;
    case VCNC_VR_B2: return &p->b2;
    case VCNC_VR_D0: return &p->d0;
    case VCNC_VR_D1: return &p->d1;
    case VCNC_VR_SAMPLE_TIME: return &p->sample_time;
    SLOT(STRIBECK_VELOCITY, &p->stribeck[0]);
    SLOT(STRIBECK_EXCESS_POSITIVE, &p->stribeck[1]);
    SLOT(STRIBECK_EXCESS_NEGATIVE, &p->stribeck[2]);
    SLOT(VISCOUS_ASYMMETRY, &p->asym);
    SLOT(POSITION_PERIOD, &p->pp_period);
    SLOT(TIME_PERIOD, &p->tp_period);
    SLOT(TIME_MEAN, &p->tp_mean);
    SLOT(DRIFT_RATE, &p->drift);
    SLOT(REFERENCE_DELAY_S, &p->ref_delay_s);
    SLOT(SETPOINT_FILTER_S, &p->filter_s);
    SLOT(PLANT_VISCOUS_RATE, &p->viscous_rate);
    SLOT(SATURATION_LIMIT, &p->saturation);
    SLOT(BACKLASH_WIDTH, &p->backlash);
    SLOT(RESONANCE_FREQUENCY, &p->res[0]);
    SLOT(RESONANCE_DAMPING, &p->res[1]);
    SLOT(RESONANCE_TABLE_FRACTION, &p->res[2]);
    default: return NULL;
    }
}

static vcnc_status bad_reference(const vcnc_instance *inst, unsigned int vr, const char *type)
{
    vcnc_logf(inst, VCNC_ERROR, "logStatusError", "value reference %u is not a %s variable of this FMU", vr, type);
    return VCNC_ERROR;
}

static vcnc_status not_now(const vcnc_instance *inst, unsigned int vr)
{
    vcnc_logf(inst, VCNC_ERROR, "logStatusError",
              "parameter with value reference %u can only be set before the end of initialisation", vr);
    return VCNC_ERROR;
}

vcnc_status vcnc_get_float(vcnc_instance *inst, const unsigned int vr[], size_t n, double values[])
{
    size_t i;
    for (i = 0; i < n; i++) {
        double *slot;
        switch (vr[i]) {
        case VCNC_VR_TIME: values[i] = vcnc_time(inst); break;
        case VCNC_VR_X_REF: values[i] = inst->s.model.x_ref; break;
        case VCNC_VR_W_EXT: values[i] = inst->s.model.w_ext; break;
        case VCNC_VR_POSITION:
        case VCNC_VR_TRACKING_ERROR: {
            double position, error;
            if (ensure_initialized(inst) != VCNC_OK) return VCNC_ERROR;
            vcnc_model_outputs(&inst->s.model, &position, &error);
            values[i] = vr[i] == VCNC_VR_POSITION ? position : error;
            break;
        }
        default:
            slot = parameter_slot(inst, vr[i]);
            if (!slot) return bad_reference(inst, vr[i], "Float64/Real");
            values[i] = *slot;
        }
    }
    return VCNC_OK;
}

vcnc_status vcnc_set_float(vcnc_instance *inst, const unsigned int vr[], size_t n, const double values[])
{
    size_t i;
    int before_step = inst->s.phase == VCNC_INSTANTIATED || inst->s.phase == VCNC_INITIALIZATION;
    for (i = 0; i < n; i++) {
        double *slot;
        switch (vr[i]) {
        case VCNC_VR_X_REF:
            inst->s.model.x_ref = values[i];
            if (before_step) inst->s.dirty = 1;
            break;
        case VCNC_VR_W_EXT: inst->s.model.w_ext = values[i]; break;
        case VCNC_VR_POSITION:
        case VCNC_VR_TRACKING_ERROR:
            vcnc_logf(inst, VCNC_ERROR, "logStatusError", "output with value reference %u cannot be set", vr[i]);
            return VCNC_ERROR;
        default:
            slot = parameter_slot(inst, vr[i]);
            if (!slot) return bad_reference(inst, vr[i], "Float64/Real");
            if (!before_step) return not_now(inst, vr[i]);
            *slot = values[i];
            inst->s.dirty = 1;
        }
    }
    return VCNC_OK;
}

vcnc_status vcnc_get_int(vcnc_instance *inst, const unsigned int vr[], size_t n, int values[])
{
    size_t i;
    for (i = 0; i < n; i++) {
        if (vr[i] != VCNC_VR_DELAY_SAMPLES || !VCNC_HAS_DELAY_SAMPLES) return bad_reference(inst, vr[i], "Int32/Integer");
        values[i] = inst->s.model.par.delay;
    }
    return VCNC_OK;
}

vcnc_status vcnc_set_int(vcnc_instance *inst, const unsigned int vr[], size_t n, const int values[])
{
    size_t i;
    int before_step = inst->s.phase == VCNC_INSTANTIATED || inst->s.phase == VCNC_INITIALIZATION;
    for (i = 0; i < n; i++) {
        if (vr[i] != VCNC_VR_DELAY_SAMPLES || !VCNC_HAS_DELAY_SAMPLES) return bad_reference(inst, vr[i], "Int32/Integer");
        if (!before_step) return not_now(inst, vr[i]);
        if (values[i] < 0 || values[i] > VCNC_MAX_DELAY) {
            vcnc_logf(inst, VCNC_ERROR, "logStatusError", "delay_samples must be in [0, %d], got %d", VCNC_MAX_DELAY,
                      values[i]);
            return VCNC_ERROR;
        }
        inst->s.model.par.delay = values[i];
        inst->s.dirty = 1;
    }
    return VCNC_OK;
}

vcnc_status vcnc_do_step(vcnc_instance *inst, double current_time, double step_size)
{
    double ts = inst->s.model.par.sample_time;
    double now = vcnc_time(inst);
    double count;
    long long k, n;

    if (inst->s.phase != VCNC_STEPPING) {
        vcnc_logf(inst, VCNC_ERROR, "logStatusError", "doStep is only allowed after initialisation");
        return VCNC_ERROR;
    }
    if (!(step_size > 0.0)) {
        vcnc_logf(inst, VCNC_ERROR, "logStatusError", "communication step size %.17g s must be > 0", step_size);
        return VCNC_ERROR;
    }
    if (fabs(current_time - now) > 1e-6 * ts + 1e-15 * fabs(now)) {
        vcnc_logf(inst, VCNC_ERROR, "logStatusError",
                  "communication point %.17g s does not match the time of the FMU (%.17g s)", current_time, now);
        return VCNC_ERROR;
    }
    count = floor(step_size / ts + 0.5);
    if (count < 1.0 || fabs(step_size - count * ts) > 1e-6 * ts || count > 9.0e15) {
        vcnc_logf(inst, VCNC_ERROR, "logStatusError",
                  "communication step size %.17g s is not a whole multiple of the sample time %.17g s of this "
                  "discrete-time model", step_size, ts);
        return VCNC_ERROR;
    }
    n = (long long)count;
    for (k = 0; k < n; k++) vcnc_model_step(&inst->s.model);
    inst->s.steps += n;
    if (vcnc_model_diverged(&inst->s.model)) {
        vcnc_logf(inst, VCNC_ERROR, "logStatusError", "the axis model diverged at t = %.17g s (unstable parameters?)",
                  vcnc_time(inst));
        return VCNC_ERROR;
    }
    return VCNC_OK;
}
