/* FMI 2.0 Co-Simulation interface of the vcnc axis model: a thin translation onto
 * vcnc_instance.c. Only the fmi2* functions are exported (the library is built with hidden
 * visibility; FMI2_Export marks these). */
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include "fmi2Functions.h"
#include "vcnc_config.h"
#include "vcnc_instance.h"

#define INST ((vcnc_instance *)c)

static void log_fmi2(const vcnc_instance *inst, vcnc_status status, const char *category, const char *message)
{
    fmi2CallbackLogger logger = (fmi2CallbackLogger)inst->callback;
    if (logger) logger((fmi2ComponentEnvironment)inst->env, inst->name, (fmi2Status)status, category, message);
}

const char *fmi2GetTypesPlatform(void) { return fmi2TypesPlatform; }
const char *fmi2GetVersion(void) { return fmi2Version; }

fmi2Status fmi2SetDebugLogging(fmi2Component c, fmi2Boolean loggingOn, size_t nCategories,
                               const fmi2String categories[])
{
    (void)nCategories;
    (void)categories;
    if (!c) return fmi2Error;
    INST->logging_on = loggingOn ? 1 : 0;
    return fmi2OK;
}

fmi2Component fmi2Instantiate(fmi2String instanceName, fmi2Type fmuType, fmi2String fmuGUID,
                              fmi2String fmuResourceLocation, const fmi2CallbackFunctions *functions,
                              fmi2Boolean visible, fmi2Boolean loggingOn)
{
    vcnc_instance *inst;
    (void)fmuResourceLocation;
    (void)visible;
    if (!functions || !functions->logger) return NULL;
    if (fmuType != fmi2CoSimulation) {
        functions->logger(functions->componentEnvironment, instanceName, fmi2Error, "logStatusError",
                          "this FMU supports Co-Simulation only");
        return NULL;
    }
    inst = vcnc_instance_new(instanceName, fmuGUID, loggingOn, log_fmi2, functions->componentEnvironment,
                             (vcnc_callback)functions->logger);
    if (!inst && fmuGUID && strcmp(fmuGUID, vcnc_token) == 0) {
        functions->logger(functions->componentEnvironment, instanceName, fmi2Error, "logStatusError",
                          "out of memory");
    }
    return (fmi2Component)inst;
}

void fmi2FreeInstance(fmi2Component c)
{
    if (c) vcnc_instance_free(INST);
}

fmi2Status fmi2SetupExperiment(fmi2Component c, fmi2Boolean toleranceDefined, fmi2Real tolerance,
                               fmi2Real startTime, fmi2Boolean stopTimeDefined, fmi2Real stopTime)
{
    (void)toleranceDefined;
    (void)tolerance;
    (void)stopTimeDefined;
    (void)stopTime;
    if (!c) return fmi2Error;
    INST->s.start_time = startTime;
    return fmi2OK;
}

fmi2Status fmi2EnterInitializationMode(fmi2Component c)
{
    if (!c) return fmi2Error;
    return (fmi2Status)vcnc_enter_initialization(INST, INST->s.start_time);
}

fmi2Status fmi2ExitInitializationMode(fmi2Component c)
{
    if (!c) return fmi2Error;
    return (fmi2Status)vcnc_exit_initialization(INST);
}

fmi2Status fmi2Terminate(fmi2Component c)
{
    if (!c) return fmi2Error;
    return (fmi2Status)vcnc_terminate(INST);
}

fmi2Status fmi2Reset(fmi2Component c)
{
    if (!c) return fmi2Error;
    vcnc_instance_reset(INST);
    return fmi2OK;
}

fmi2Status fmi2GetReal(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2Real value[])
{
    if (!c) return fmi2Error;
    return (fmi2Status)vcnc_get_float(INST, vr, nvr, value);
}

fmi2Status fmi2GetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2Integer value[])
{
    if (!c) return fmi2Error;
    return (fmi2Status)vcnc_get_int(INST, vr, nvr, value);
}

fmi2Status fmi2GetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2Boolean value[])
{
    (void)value;
    if (!c) return fmi2Error;
    if (nvr == 0) return fmi2OK;
    vcnc_logf(INST, VCNC_ERROR, "logStatusError", "value reference %u is not a Boolean variable", vr[0]);
    return fmi2Error;
}

fmi2Status fmi2GetString(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2String value[])
{
    (void)value;
    if (!c) return fmi2Error;
    if (nvr == 0) return fmi2OK;
    vcnc_logf(INST, VCNC_ERROR, "logStatusError", "value reference %u is not a String variable", vr[0]);
    return fmi2Error;
}

fmi2Status fmi2SetReal(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2Real value[])
{
    if (!c) return fmi2Error;
    return (fmi2Status)vcnc_set_float(INST, vr, nvr, value);
}

fmi2Status fmi2SetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2Integer value[])
{
    if (!c) return fmi2Error;
    return (fmi2Status)vcnc_set_int(INST, vr, nvr, value);
}

fmi2Status fmi2SetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2Boolean value[])
{
    (void)value;
    if (!c) return fmi2Error;
    if (nvr == 0) return fmi2OK;
    vcnc_logf(INST, VCNC_ERROR, "logStatusError", "value reference %u is not a Boolean variable", vr[0]);
    return fmi2Error;
}

fmi2Status fmi2SetString(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2String value[])
{
    (void)value;
    if (!c) return fmi2Error;
    if (nvr == 0) return fmi2OK;
    vcnc_logf(INST, VCNC_ERROR, "logStatusError", "value reference %u is not a String variable", vr[0]);
    return fmi2Error;
}

/* FMU state: a copy of the snapshot; serialised as its bytes (same binary only). */
fmi2Status fmi2GetFMUstate(fmi2Component c, fmi2FMUstate *FMUstate)
{
    vcnc_snapshot *s;
    if (!c || !FMUstate) return fmi2Error;
    s = (vcnc_snapshot *)(*FMUstate ? *FMUstate : malloc(sizeof(vcnc_snapshot)));
    if (!s) return fmi2Error;
    memcpy(s, &INST->s, sizeof(vcnc_snapshot));
    *FMUstate = (fmi2FMUstate)s;
    return fmi2OK;
}

fmi2Status fmi2SetFMUstate(fmi2Component c, fmi2FMUstate FMUstate)
{
    if (!c || !FMUstate) return fmi2Error;
    memcpy(&INST->s, FMUstate, sizeof(vcnc_snapshot));
    return fmi2OK;
}

fmi2Status fmi2FreeFMUstate(fmi2Component c, fmi2FMUstate *FMUstate)
{
    (void)c;
    if (FMUstate && *FMUstate) {
        free(*FMUstate);
        *FMUstate = NULL;
    }
    return fmi2OK;
}

fmi2Status fmi2SerializedFMUstateSize(fmi2Component c, fmi2FMUstate FMUstate, size_t *size)
{
    (void)c;
    (void)FMUstate;
    *size = sizeof(vcnc_snapshot);
    return fmi2OK;
}

fmi2Status fmi2SerializeFMUstate(fmi2Component c, fmi2FMUstate FMUstate, fmi2Byte serializedState[], size_t size)
{
    if (!c || !FMUstate || size != sizeof(vcnc_snapshot)) return fmi2Error;
    memcpy(serializedState, FMUstate, sizeof(vcnc_snapshot));
    return fmi2OK;
}

fmi2Status fmi2DeSerializeFMUstate(fmi2Component c, const fmi2Byte serializedState[], size_t size,
                                   fmi2FMUstate *FMUstate)
{
    if (!c || !FMUstate || size != sizeof(vcnc_snapshot)) return fmi2Error;
    if (!*FMUstate) *FMUstate = malloc(sizeof(vcnc_snapshot));
    if (!*FMUstate) return fmi2Error;
    memcpy(*FMUstate, serializedState, sizeof(vcnc_snapshot));
    return fmi2OK;
}

fmi2Status fmi2GetDirectionalDerivative(fmi2Component c, const fmi2ValueReference vUnknown_ref[], size_t nUnknown,
                                        const fmi2ValueReference vKnown_ref[], size_t nKnown,
                                        const fmi2Real dvKnown[], fmi2Real dvUnknown[])
{
    (void)vUnknown_ref; (void)nUnknown; (void)vKnown_ref; (void)nKnown; (void)dvKnown; (void)dvUnknown;
    if (!c) return fmi2Error;
    return (fmi2Status)vcnc_unsupported(INST, "fmi2GetDirectionalDerivative");
}

/* Co-Simulation */

fmi2Status fmi2SetRealInputDerivatives(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                                       const fmi2Integer order[], const fmi2Real value[])
{
    (void)vr; (void)nvr; (void)order; (void)value;
    if (!c) return fmi2Error;
    return (fmi2Status)vcnc_unsupported(INST, "fmi2SetRealInputDerivatives");
}

fmi2Status fmi2GetRealOutputDerivatives(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                                        const fmi2Integer order[], fmi2Real value[])
{
    (void)vr; (void)nvr; (void)order; (void)value;
    if (!c) return fmi2Error;
    return (fmi2Status)vcnc_unsupported(INST, "fmi2GetRealOutputDerivatives");
}

fmi2Status fmi2DoStep(fmi2Component c, fmi2Real currentCommunicationPoint, fmi2Real communicationStepSize,
                      fmi2Boolean noSetFMUStatePriorToCurrentPoint)
{
    (void)noSetFMUStatePriorToCurrentPoint;
    if (!c) return fmi2Error;
    return (fmi2Status)vcnc_do_step(INST, currentCommunicationPoint, communicationStepSize);
}

fmi2Status fmi2CancelStep(fmi2Component c)
{
    if (!c) return fmi2Error;
    return (fmi2Status)vcnc_unsupported(INST, "fmi2CancelStep (doStep is synchronous)");
}

fmi2Status fmi2GetStatus(fmi2Component c, const fmi2StatusKind s, fmi2Status *value)
{
    (void)s;
    (void)value;
    if (!c) return fmi2Error;
    return (fmi2Status)vcnc_unsupported(INST, "fmi2GetStatus");
}

fmi2Status fmi2GetRealStatus(fmi2Component c, const fmi2StatusKind s, fmi2Real *value)
{
    if (!c) return fmi2Error;
    if (s == fmi2LastSuccessfulTime) {
        *value = vcnc_time(INST);
        return fmi2OK;
    }
    return (fmi2Status)vcnc_unsupported(INST, "fmi2GetRealStatus for this status kind");
}

fmi2Status fmi2GetIntegerStatus(fmi2Component c, const fmi2StatusKind s, fmi2Integer *value)
{
    (void)s;
    (void)value;
    if (!c) return fmi2Error;
    return (fmi2Status)vcnc_unsupported(INST, "fmi2GetIntegerStatus");
}

fmi2Status fmi2GetBooleanStatus(fmi2Component c, const fmi2StatusKind s, fmi2Boolean *value)
{
    if (!c) return fmi2Error;
    if (s == fmi2Terminated) {
        *value = fmi2False;
        return fmi2OK;
    }
    return (fmi2Status)vcnc_unsupported(INST, "fmi2GetBooleanStatus for this status kind");
}

fmi2Status fmi2GetStringStatus(fmi2Component c, const fmi2StatusKind s, fmi2String *value)
{
    (void)s;
    (void)value;
    if (!c) return fmi2Error;
    return (fmi2Status)vcnc_unsupported(INST, "fmi2GetStringStatus");
}
