/*
 * modelDescription.xml of a case's FMU (FMI 2.0, chapter 2.2 and 4.3.1; the schema
 * fmi2ModelDescription.xsd): co-simulation only, one ScalarVariable per td_fmu_var in value
 * reference order (so the index of variable vr in ModelVariables is vr + 1, which ModelStructure
 * names), the units in SI base units (2.2.2), the case's end time as the default experiment.
 */
#include "fmu/fmu_internal.h"
#include "touchdown/version.h"
#include "util/error_internal.h"
#include "util/text.h"

#include <stdlib.h>
#include <string.h>

/* s with the XML escapes; characters XML 1.0 does not allow (controls other than tab, newline,
 * return) as spaces. */
static void xml_text(td_text *t, const char *s)
{
    for (; *s; s++) {
        unsigned char c = (unsigned char)*s;
        if (c == '&')
            td_text_printf(t, "&amp;");
        else if (c == '<')
            td_text_printf(t, "&lt;");
        else if (c == '>')
            td_text_printf(t, "&gt;");
        else if (c == '"')
            td_text_printf(t, "&quot;");
        else if ((c < 0x20 && c != '\t' && c != '\n' && c != '\r') || c == 0x7f)
            td_text_append(t, " ", 1);
        else
            td_text_append(t, s, 1);
    }
}

/* A unit and its exponents of the SI base units kg, m, s, A and of rad (2.2.2 BaseUnit). */
typedef struct unit_def {
    const char *name;
    int kg, m, s, A, rad;
} unit_def;

static const unit_def units[] = {{"m", 0, 1, 0, 0, 0},      {"N", 1, 1, -2, 0, 0},  {"A", 0, 0, 0, 1, 0},
                                 {"rad/s", 0, 0, -1, 0, 1}, {"rad", 0, 0, 0, 0, 1}, {"s", 0, 0, 1, 0, 0},
                                 {"kg.m", 1, 1, 0, 0, 0}};

static void unit_definitions(td_text *t)
{
    size_t i;
    td_text_printf(t, "  <UnitDefinitions>\n");
    for (i = 0; i < sizeof units / sizeof units[0]; i++) {
        const unit_def *u = &units[i];
        td_text_printf(t, "    <Unit name=\"%s\"><BaseUnit", u->name);
        if (u->kg)
            td_text_printf(t, " kg=\"%d\"", u->kg);
        if (u->m)
            td_text_printf(t, " m=\"%d\"", u->m);
        if (u->s)
            td_text_printf(t, " s=\"%d\"", u->s);
        if (u->A)
            td_text_printf(t, " A=\"%d\"", u->A);
        if (u->rad)
            td_text_printf(t, " rad=\"%d\"", u->rad);
        td_text_printf(t, "/></Unit>\n");
    }
    td_text_printf(t, "  </UnitDefinitions>\n");
}

const td_fmu_log_category_def td_fmu_log_categories[TD_FMU_LOG_CATEGORIES] = {
    {"logEvents", "an event inside a communication step: a contact, a mode change, a controller's event"},
    {"logStatusDiscard", "a status query the FMU has no answer for (fmi2Discard)"},
    {"logStatusError", "a refused call or a failed step (fmi2Error), always logged"}};

/* LogCategories (2.2.4), after UnitDefinitions and TypeDefinitions, before DefaultExperiment. */
static void log_categories(td_text *t)
{
    int i;
    td_text_printf(t, "  <LogCategories>\n");
    for (i = 0; i < TD_FMU_LOG_CATEGORIES; i++) {
        td_text_printf(t, "    <Category name=\"%s\" description=\"", td_fmu_log_categories[i].name);
        xml_text(t, td_fmu_log_categories[i].description);
        td_text_printf(t, "\"/>\n");
    }
    td_text_printf(t, "  </LogCategories>\n");
}

/* The type element of v: <Real unit=".." start=".."/>, <Integer/>, <Boolean/>. */
static void type_element(td_text *t, const td_fmu_var *v)
{
    static const char *const names[] = {"Real", "Integer", "Boolean"};
    td_text_printf(t, "<%s", names[v->type]);
    if (v->unit[0] && strcmp(v->unit, "1") != 0)
        td_text_printf(t, " unit=\"%s\"", v->unit);
    if (v->causality != TD_FMU_OUTPUT) /* parameters (exact) and inputs carry a start value */
        td_text_printf(t, " start=\"%.17g\"", v->start);
    td_text_printf(t, "/>");
}

static void scalar_variable(td_text *t, const td_fmu_var *v)
{
    static const char *const causality[] = {"parameter", "input", "output"};
    const char *variability = v->causality == TD_FMU_PARAMETER ? "fixed"
                              : v->type == TD_FMU_REAL         ? "continuous"
                                                               : "discrete";
    td_text_printf(t, "    <ScalarVariable name=\"");
    xml_text(t, v->name);
    td_text_printf(t, "\" valueReference=\"%u\" causality=\"%s\" variability=\"%s\"", v->vr, causality[v->causality],
                   variability);
    if (v->causality == TD_FMU_PARAMETER)
        td_text_printf(t, " initial=\"exact\"");
    td_text_printf(t, " description=\"");
    xml_text(t, v->description);
    td_text_printf(t, "\">\n      ");
    type_element(t, v);
    td_text_printf(t, "\n    </ScalarVariable>\n");
}

/* ModelStructure: every output, all of them also initial unknowns (calculated at initialisation). */
static void model_structure(td_text *t, const td_fmu_var *v, int n)
{
    int i, pass;
    td_text_printf(t, "  <ModelStructure>\n");
    for (pass = 0; pass < 2; pass++) {
        td_text_printf(t, "    <%s>\n", pass ? "InitialUnknowns" : "Outputs");
        for (i = 0; i < n; i++)
            if (v[i].causality == TD_FMU_OUTPUT)
                td_text_printf(t, "      <Unknown index=\"%d\"/>\n", i + 1);
        td_text_printf(t, "    </%s>\n", pass ? "InitialUnknowns" : "Outputs");
    }
    td_text_printf(t, "  </ModelStructure>\n");
}

static void header(td_text *t, const td_case *c, td_fmu_inputs inputs, const char *id, const char *guid)
{
    td_text_printf(t, "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
    td_text_printf(t, "<fmiModelDescription fmiVersion=\"2.0\" modelName=\"");
    xml_text(t, td_case_name(c));
    td_text_printf(t, "\" guid=\"%s\" description=\"", guid);
    xml_text(t, td_case_description(c));
    td_text_printf(t, "\" generationTool=\"touchdown %s (inputs: %s)\" variableNamingConvention=\"structured\"",
                   TD_VERSION, td_fmu_inputs_name(inputs));
    td_text_printf(t, " numberOfEventIndicators=\"0\">\n");
    td_text_printf(
        t,
        "  <CoSimulation modelIdentifier=\"%s\" needsExecutionTool=\"false\""
        " canHandleVariableCommunicationStepSize=\"true\" canInterpolateInputs=\"false\""
        " maxOutputDerivativeOrder=\"0\" canRunAsynchronuously=\"false\" canBeInstantiatedOnlyOncePerProcess=\"false\""
        " canNotUseMemoryManagementFunctions=\"true\" canGetAndSetFMUstate=\"false\""
        " canSerializeFMUstate=\"false\" providesDirectionalDerivative=\"false\"/>\n",
        id);
}

td_status td_fmu_model_description(const td_case *c, td_fmu_inputs inputs, const char *id, const char *guid, td_text *t,
                                   td_error *err)
{
    td_fmu_var *v;
    int i, n;
    td_status st = td_fmu_variables(td_case_model(c), inputs, &v, &n, err);
    if (st != TD_OK)
        return st;
    header(t, c, inputs, id, guid);
    unit_definitions(t);
    log_categories(t);
    td_text_printf(t, "  <DefaultExperiment startTime=\"%.17g\" stopTime=\"%.17g\"/>\n", td_case_sim_options(c)->t0,
                   td_case_end_time(c));
    td_text_printf(t, "  <ModelVariables>\n");
    for (i = 0; i < n; i++)
        scalar_variable(t, &v[i]);
    td_text_printf(t, "  </ModelVariables>\n");
    model_structure(t, v, n);
    td_text_printf(t, "</fmiModelDescription>\n");
    free(v);
    return t->failed ? td_error_set(err, TD_ERR_NOMEM, "out of memory writing the model description") : TD_OK;
}
