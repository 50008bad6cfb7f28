/*
 * A minimal fixed-step FMI 2.0 Co-Simulation master, written like the co-simulation loop of
 * the FMI reference examples (modelica/Reference-FMUs, fmusim): it loads the binary of an
 * unzipped FMU with dlopen, instantiates it with the GUID of its modelDescription.xml,
 * declares the stop time in fmi2SetupExperiment, sets parameters by value reference, steps
 * with a fixed communication step to the stop time and prints the outputs as CSV.
 *
 *   master UNZIPDIR [-r VR=VALUE]... [-i VR=VALUE]... [-o VR[:NAME]]...
 *          [--start T0] [--stop T1] [--step H]
 *
 *   -r, -i   set a Real or Integer (also Enumeration) variable before initialization
 *   -o       an output (Real) to print; NAME is the CSV column header (default: the VR)
 *   --start, --stop, --step   override the DefaultExperiment of modelDescription.xml
 *
 * Communication points are t_k = t0 + k h, k = 0 .. n with n = round((t1 - t0) / h): a
 * fixed-step master needs stop - start to be a whole number of steps (the FMU refuses a
 * step that ends after stopTime). Each row is printed after the step that reaches t_k (the
 * first row after fmi2ExitInitializationMode). Any status other than fmi2OK or fmi2Warning
 * ends the run with exit code 1; FMU messages go to stderr.
 *
 * Build: gcc -std=c99 -Wall -Wextra -O1 -o master master.c -ldl
 */

#define _GNU_SOURCE
#include <dlfcn.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The FMI 2.0 types this master uses (fmi2TypesPlatform.h, fmi2FunctionTypes.h). */
typedef void *fmi2Component;
typedef void *fmi2ComponentEnvironment;
typedef unsigned int fmi2ValueReference;
typedef double fmi2Real;
typedef int fmi2Integer;
typedef int fmi2Boolean;
typedef const char *fmi2String;
typedef enum { fmi2OK, fmi2Warning, fmi2Discard, fmi2Error, fmi2Fatal, fmi2Pending } fmi2Status;
typedef enum { fmi2ModelExchange, fmi2CoSimulation } fmi2Type;

typedef void (*fmi2CallbackLogger)(fmi2ComponentEnvironment, fmi2String, fmi2Status, fmi2String,
                                   fmi2String, ...);
typedef struct {
    fmi2CallbackLogger logger;
    void *(*allocateMemory)(size_t, size_t);
    void (*freeMemory)(void *);
    void (*stepFinished)(fmi2ComponentEnvironment, fmi2Status);
    fmi2ComponentEnvironment componentEnvironment;
} fmi2CallbackFunctions;

typedef fmi2Component (*fmi2InstantiateTYPE)(fmi2String, fmi2Type, fmi2String, fmi2String,
                                             const fmi2CallbackFunctions *, fmi2Boolean,
                                             fmi2Boolean);
typedef void (*fmi2FreeInstanceTYPE)(fmi2Component);
typedef fmi2Status (*fmi2SetupExperimentTYPE)(fmi2Component, fmi2Boolean, fmi2Real, fmi2Real,
                                              fmi2Boolean, fmi2Real);
typedef fmi2Status (*fmi2ComponentTYPE)(fmi2Component);
typedef fmi2Status (*fmi2GetRealTYPE)(fmi2Component, const fmi2ValueReference *, size_t,
                                      fmi2Real *);
typedef fmi2Status (*fmi2SetRealTYPE)(fmi2Component, const fmi2ValueReference *, size_t,
                                      const fmi2Real *);
typedef fmi2Status (*fmi2SetIntegerTYPE)(fmi2Component, const fmi2ValueReference *, size_t,
                                         const fmi2Integer *);
typedef fmi2Status (*fmi2DoStepTYPE)(fmi2Component, fmi2Real, fmi2Real, fmi2Boolean);

#define MAX_VARS 64

static const char *status_name(fmi2Status s) {
    static const char *names[] = {"fmi2OK",    "fmi2Warning", "fmi2Discard",
                                  "fmi2Error", "fmi2Fatal",   "fmi2Pending"};
    return (s >= fmi2OK && s <= fmi2Pending) ? names[s] : "unknown status";
}

static void logger(fmi2ComponentEnvironment env, fmi2String instance, fmi2Status status,
                   fmi2String category, fmi2String message, ...) {
    (void)env;
    va_list args;
    va_start(args, message);
    fprintf(stderr, "[%s] %s %s: ", status_name(status), instance ? instance : "?",
            category ? category : "?");
    vfprintf(stderr, message, args);
    fputc('\n', stderr);
    va_end(args);
}

static void fail(const char *what) {
    fprintf(stderr, "master: %s\n", what);
    exit(1);
}

static void check(fmi2Status s, const char *call) {
    if (s != fmi2OK && s != fmi2Warning) {
        fprintf(stderr, "master: %s returned %s\n", call, status_name(s));
        exit(1);
    }
}

/* The whole file as a string. */
static char *read_file(const char *path) {
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    char *text = malloc((size_t)n + 1);
    if (!text || fread(text, 1, (size_t)n, f) != (size_t)n) fail("cannot read modelDescription.xml");
    text[n] = '\0';
    fclose(f);
    return text;
}

/* The value of attribute `name` of the first element `element` (a plain text search: enough
 * for the attributes of <fmiModelDescription>, <CoSimulation> and <DefaultExperiment>). */
static int attribute(const char *xml, const char *element, const char *name, char *out,
                     size_t size) {
    char open[64], key[64];
    snprintf(open, sizeof open, "<%s ", element);
    snprintf(key, sizeof key, " %s=\"", name);
    const char *e = strstr(xml, open);
    if (!e) return 0;
    const char *end = strchr(e, '>');
    const char *a = strstr(e, key);
    if (!a || (end && a > end)) return 0;
    a += strlen(key);
    const char *q = strchr(a, '"');
    if (!q || (size_t)(q - a) >= size) return 0;
    memcpy(out, a, (size_t)(q - a));
    out[q - a] = '\0';
    return 1;
}

static void *symbol(void *library, const char *name) {
    void *f = dlsym(library, name);
    if (!f) {
        fprintf(stderr, "master: the FMU binary has no %s\n", name);
        exit(1);
    }
    return f;
}

int main(int argc, char **argv) {
    if (argc < 2) fail("usage: master UNZIPDIR [-r VR=VALUE]... [-i VR=VALUE]... [-o VR[:NAME]]...");
    const char *dir = argv[1];

    fmi2ValueReference real_vr[MAX_VARS], int_vr[MAX_VARS], out_vr[MAX_VARS];
    fmi2Real real_value[MAX_VARS];
    fmi2Integer int_value[MAX_VARS];
    const char *out_name[MAX_VARS];
    size_t n_real = 0, n_int = 0, n_out = 0;
    double start = NAN, stop = NAN, step = NAN;

    for (int k = 2; k < argc; k++) {
        const char *arg = argv[k];
        if (k + 1 >= argc) fail("an option without its value");
        const char *value = argv[++k];
        char *rest;
        if (!strcmp(arg, "-r") || !strcmp(arg, "-i")) {
            unsigned long vr = strtoul(value, &rest, 10);
            if (*rest != '=') fail("-r and -i take VR=VALUE");
            if (n_real >= MAX_VARS || n_int >= MAX_VARS) fail("too many values");
            if (arg[1] == 'r') {
                real_vr[n_real] = (fmi2ValueReference)vr;
                real_value[n_real++] = strtod(rest + 1, NULL);
            } else {
                int_vr[n_int] = (fmi2ValueReference)vr;
                int_value[n_int++] = (fmi2Integer)strtol(rest + 1, NULL, 10);
            }
        } else if (!strcmp(arg, "-o")) {
            if (n_out >= MAX_VARS) fail("too many outputs");
            out_vr[n_out] = (fmi2ValueReference)strtoul(value, &rest, 10);
            out_name[n_out++] = (*rest == ':') ? rest + 1 : value;
        } else if (!strcmp(arg, "--start")) {
            start = strtod(value, NULL);
        } else if (!strcmp(arg, "--stop")) {
            stop = strtod(value, NULL);
        } else if (!strcmp(arg, "--step")) {
            step = strtod(value, NULL);
        } else {
            fail("unknown option");
        }
    }

    /* modelDescription.xml: GUID, model identifier, default experiment. */
    char path[4096], guid[128], identifier[256], text[64];
    snprintf(path, sizeof path, "%s/modelDescription.xml", dir);
    char *xml = read_file(path);
    if (!xml) fail("cannot open modelDescription.xml");
    if (!attribute(xml, "fmiModelDescription", "guid", guid, sizeof guid)) fail("no guid");
    if (!attribute(xml, "CoSimulation", "modelIdentifier", identifier, sizeof identifier))
        fail("no CoSimulation modelIdentifier");
    if (isnan(start) && attribute(xml, "DefaultExperiment", "startTime", text, sizeof text))
        start = strtod(text, NULL);
    if (isnan(stop) && attribute(xml, "DefaultExperiment", "stopTime", text, sizeof text))
        stop = strtod(text, NULL);
    if (isnan(step) && attribute(xml, "DefaultExperiment", "stepSize", text, sizeof text))
        step = strtod(text, NULL);
    free(xml);
    if (isnan(start)) start = 0.0;
    if (isnan(stop) || isnan(step) || !(step > 0.0) || !(stop > start))
        fail("no usable start, stop and step (DefaultExperiment or --start/--stop/--step)");
    long n_steps = lround((stop - start) / step);
    if (n_steps < 1 || fabs(start + n_steps * step - stop) > 1e-9 * fabs(stop - start))
        fail("stop - start is not a whole number of steps");

    /* The binary. */
    snprintf(path, sizeof path, "%s/binaries/linux64/%s.so", dir, identifier);
    void *library = dlopen(path, RTLD_NOW | RTLD_LOCAL);
    if (!library) {
        fprintf(stderr, "master: dlopen %s: %s\n", path, dlerror());
        return 1;
    }
    fmi2InstantiateTYPE instantiate = (fmi2InstantiateTYPE)symbol(library, "fmi2Instantiate");
    fmi2FreeInstanceTYPE free_instance = (fmi2FreeInstanceTYPE)symbol(library, "fmi2FreeInstance");
    fmi2SetupExperimentTYPE setup = (fmi2SetupExperimentTYPE)symbol(library, "fmi2SetupExperiment");
    fmi2ComponentTYPE enter = (fmi2ComponentTYPE)symbol(library, "fmi2EnterInitializationMode");
    fmi2ComponentTYPE exit_init = (fmi2ComponentTYPE)symbol(library, "fmi2ExitInitializationMode");
    fmi2ComponentTYPE terminate = (fmi2ComponentTYPE)symbol(library, "fmi2Terminate");
    fmi2GetRealTYPE get_real = (fmi2GetRealTYPE)symbol(library, "fmi2GetReal");
    fmi2SetRealTYPE set_real = (fmi2SetRealTYPE)symbol(library, "fmi2SetReal");
    fmi2SetIntegerTYPE set_integer = (fmi2SetIntegerTYPE)symbol(library, "fmi2SetInteger");
    fmi2DoStepTYPE do_step = (fmi2DoStepTYPE)symbol(library, "fmi2DoStep");

    /* Instantiate with the resources of the unzipped FMU. */
    char resources[4200];
    snprintf(resources, sizeof resources, "file://%s/resources", dir);
    fmi2CallbackFunctions callbacks = {logger, calloc, free, NULL, NULL};
    fmi2Component c = instantiate("c_master", fmi2CoSimulation, guid, resources, &callbacks, 0, 0);
    if (!c) fail("fmi2Instantiate returned NULL");

    /* Setup with the stop time, parameters, initialization. */
    check(setup(c, 0, 0.0, start, 1, stop), "fmi2SetupExperiment");
    if (n_real) check(set_real(c, real_vr, n_real, real_value), "fmi2SetReal");
    if (n_int) check(set_integer(c, int_vr, n_int, int_value), "fmi2SetInteger");
    check(enter(c), "fmi2EnterInitializationMode");
    check(exit_init(c), "fmi2ExitInitializationMode");

    /* The fixed-step loop. */
    fmi2Real values[MAX_VARS];
    printf("time");
    for (size_t i = 0; i < n_out; i++) printf(",%s", out_name[i]);
    printf("\n");
    for (long k = 0;; k++) {
        double time = start + k * step;
        if (n_out) check(get_real(c, out_vr, n_out, values), "fmi2GetReal");
        printf("%.17g", time);
        for (size_t i = 0; i < n_out; i++) printf(",%.17g", values[i]);
        printf("\n");
        if (k == n_steps) break;
        check(do_step(c, time, step, 1), "fmi2DoStep");
    }

    check(terminate(c), "fmi2Terminate");
    free_instance(c);
    dlclose(library);
    return 0;
}
