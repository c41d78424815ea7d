/* touchdown info: what a case describes, and its first modes. */
#include "common/cli.h"
#include "info/controller_print.h"
#include "info/recovery_print.h"
#include "modal/modal_print.h"

#include <getopt.h>
#include <stdlib.h>

static const char info_usage[] =
    "usage: touchdown info [OPTIONS] CASE\n"
    "       touchdown info --keys\n"
    "\n"
    "Print what CASE describes: shaft nodes and elements, masses, AMBs, plain bearings,\n"
    "retainers, unbalances, the schedule, the controllers (their AMBs, coordinates, states,\n"
    "timing and poles; a plug-in's library, ABI, timing and parameters), the recovery supervisor (its pairs and "
    "rules), the speed (constant, a ramp or a free spin) and "
    "the\n"
    "rotor's polar inertia, DOF and state counts, and the first modes of the\n"
    "contact-free system at the case speed. Large models get only the lowest modes (shift-invert\n"
    "Arnoldi); their stability line then covers the roots computed, not all of them.\n"
    "\n"
    "options:\n"
    "  -s, --set KEY=VALUE  override a case key (repeatable)\n"
    "  -n, --modes N        number of modes to list (default 6)\n"
    "      --keys           print every case key the reader knows (no CASE): one JSON object a\n"
    "                       line with its section, key, type, range, unit, default and doc, in\n"
    "                       a JSON array (docs/case-format.md's key tables are made from it)\n"
    "  -h, --help           this help\n";

/* The race, mount, own contact law and stick state of a retainer, when it has them. */
static void print_race(const td_retainer *r)
{
    const td_race *b = &r->race;
    if (r->stick)
        printf("             stick: rolling without slip is a state\n");
    if (b->inertia > 0.0)
        printf("             race: inertia %.6g kg m^2, drag %.6g N m + %.6g N m s/rad\n", b->inertia, b->drag_torque,
               b->drag_viscous);
    if (b->mount_stiffness > 0.0)
        printf("             mount: race mass %.6g kg, stiffness %.6g N/m, damping %.6g N s/m\n", b->mass,
               b->mount_stiffness, b->mount_damping);
    if (r->contact.stiffness > 0.0)
        printf("             contact: stiffness %.6g N/m^%.6g, damping %s %.6g\n", r->contact.stiffness,
               r->contact.exponent > 0.0 ? r->contact.exponent : 1.0, /* 0: not given, taken as 1 */
               r->contact.damping == TD_DAMPING_KELVIN_VOIGT    ? "kelvin-voigt"
               : r->contact.damping == TD_DAMPING_HUNT_CROSSLEY ? "hunt-crossley"
                                                                : "none",
               r->contact.damping_coefficient);
}

/* heat: retainer i's thermal network, when it has one. */
static void print_thermal(const td_model *m, int i)
{
    td_retainer_thermal t;
    if (!td_model_get_retainer_thermal(m, i, &t))
        return;
    printf("             thermal: race %.6g J/K, housing %.6g J/K, race-housing %.6g W/K, housing-ambient %.6g W/K",
           t.race_capacity, t.housing_capacity, t.race_housing_conductance, t.housing_ambient_conductance);
    if (td_is_undefined(t.expansion))
        printf("\n");
    else
        printf(", expansion %.6g 1/K (growth reported, not fed back)\n", t.expansion);
}

/* The AMBs: magnet, law (the shorthand's gains, or the controller that drives it) and amplifier. */
static void print_ambs(const td_model *m)
{
    int i;
    for (i = 0; i < td_model_amb_count(m); i++) {
        td_amb a;
        int k = td_amb_controller(m, i);
        td_model_get_amb(m, i, &a);
        printf("amb %-8d node %d (sensor %d): ks %.6g N/m, ki %.6g N/A, ", i, a.node, a.sensor_node, a.ks, a.ki);
        if (k >= 0)
            printf("controller %d, ", k);
        else
            printf("kp %.6g A/m, kd %.6g A s/m, ", a.kp, a.kd);
        if (a.kint > 0.0)
            printf("kint %.6g A/(m s), ", a.kint);
        printf("tau %.6g s, ", a.tau);
        if (a.slew_rate > 0.0)
            printf("slew rate %.6g A/s, ", a.slew_rate);
        printf("capacity %.6g N%s\n", a.force_capacity, a.saturation ? " (saturating)" : "");
    }
}

static void print_parts(const td_model *m)
{
    int i;
    double disc_mass = 0.0;
    td_shaft_options so;
    td_model_shaft_options(m, &so);
    printf("shaft        %d elements, %d nodes, length %.6g m, %s, %s mass\n", td_model_shaft_element_count(m),
           td_model_node_count(m), td_model_node_position(m, td_model_node_count(m) - 1),
           so.beam == TD_BEAM_TIMOSHENKO ? "Timoshenko" : "Euler-Bernoulli",
           so.mass == TD_MASS_LUMPED ? "lumped" : "consistent");
    if (so.beam == TD_BEAM_TIMOSHENKO && so.shear == TD_SHEAR_GIVEN)
        printf("shear        coefficient kappa %.6g (given)\n", so.shear_value);
    else if (so.beam == TD_BEAM_TIMOSHENKO)
        printf("shear        coefficient kappa of %s for the hollow circle\n",
               so.shear == TD_SHEAR_COWPER ? "Cowper (1966)" : "Hutchinson (2001)");
    if (so.rayleigh_alpha > 0.0 || so.rayleigh_beta > 0.0)
        printf("damping      shaft Rayleigh alpha %.6g 1/s, beta %.6g s: zeta(w) = alpha / (2 w) + beta w / 2\n",
               so.rayleigh_alpha, so.rayleigh_beta);
    for (i = 0; i < td_model_disc_count(m); i++) {
        td_disc d;
        td_model_get_disc(m, i, &d);
        disc_mass += d.mass;
        if (d.Ip > 0.0 || d.Id > 0.0)
            printf("disc         node %d: m %.6g kg, Ip %.6g kg m^2, Id %.6g kg m^2\n", d.node, d.mass, d.Ip, d.Id);
        else
            printf("point mass   node %d: %.6g kg\n", d.node, d.mass);
    }
    printf("mass         %.6f kg in all (shaft %.6f kg, discs and point masses %.6f kg)\n", td_model_total_mass(m),
           td_model_total_mass(m) - disc_mass, disc_mass);
    print_ambs(m);
    for (i = 0; i < td_model_bearing_count(m); i++) {
        td_bearing b;
        td_model_get_bearing(m, i, &b);
        printf("bearing %-4d node %d: kxx %.6g kyy %.6g N/m, cxx %.6g cyy %.6g N s/m\n", i, b.node, b.kxx, b.kyy, b.cxx,
               b.cyy);
    }
    for (i = 0; i < td_model_retainer_count(m); i++) {
        td_retainer r;
        td_model_get_retainer(m, i, &r);
        printf("retainer %-3d node %d: clearance %.6g m, Rs %.6g m, Rb %.6g m, mu %.6g, bore speed %.6g rad/s, "
               "restitution %.6g\n",
               i, r.node, r.clearance, r.shaft_radius, r.bore_radius, r.friction, r.bore_speed, r.restitution);
        print_race(&r);
        print_thermal(m, i); /* heat */
    }
    for (i = 0; i < td_model_unbalance_count(m); i++) {
        td_unbalance u;
        td_model_get_unbalance(m, i, &u);
        printf("unbalance %-2d node %d: %.6g kg m at %.6g rad\n", i, u.node, u.magnitude, u.phase);
    }
    for (i = 0; i < td_model_change_count(m); i++) {
        td_change ch;
        td_model_get_change(m, i, &ch);
        if (ch.kind == TD_CHANGE_UNBALANCE)
            printf("at t = %-7.6g unbalance %d becomes %.6g kg m at %.6g rad\n", ch.time, ch.index, ch.magnitude,
                   ch.phase);
        else
            printf("at t = %-7.6g amb %d %s\n", ch.time, ch.index, ch.kind == TD_CHANGE_AMB_OFF ? "fails" : "restored");
    }
}

/* The speed: constant, a ramp's points, or a free spin with its torques; and the polar inertia. */
static void print_speed(const td_model *m)
{
    td_spin sp;
    int i, n = td_model_speed_point_count(m);
    td_model_spin(m, &sp);
    printf("speed        %.9g rad/s (%.9g rpm)%s\n", td_model_speed(m), TD_RPM_FROM_RAD_S(td_model_speed(m)),
           n > 0     ? ", then the ramp"
           : sp.free ? " at the start, free"
                     : "");
    for (i = 0; i < n; i++) {
        td_speed_point p;
        td_model_get_speed_point(m, i, &p);
        printf("  ramp       at t = %.9g s: %.9g rad/s\n", p.time, p.speed);
    }
    printf("polar        J = %.6g kg m^2 (shaft and discs)%s\n", td_model_polar_inertia(m),
           sp.free && sp.inertia > 0.0 ? "; the spin uses spin.inertia" : "");
    if (sp.free)
        printf("spin         free: drive %.6g N m, drag %.6g N m + %.6g N m s/rad%s\n", sp.drive_torque, sp.drag_torque,
               sp.drag_viscous, sp.inertia > 0.0 ? "" : ", J as above");
}

/* One member "name": "value" of a key's JSON line. */
static void print_member(const char *name, const char *value, const char *after)
{
    char buf[2048];
    td_json_string(buf, sizeof buf, value);
    printf("\"%s\": %s%s", name, buf, after);
}

/* touchdown info --keys: the case schema (td_case_key), a JSON array with one key a line. */
static int print_keys(void)
{
    td_case_key_info k;
    td_error err;
    int i, n = td_case_key_count();
    printf("[\n");
    for (i = 0; i < n; i++) {
        if (td_case_key(i, &k, &err) != TD_OK) {
            fprintf(stderr, "touchdown info: %s\n", err.message);
            return TD_EXIT_FAILED;
        }
        printf(" {");
        print_member("section", k.section, ", ");
        print_member("key", k.key, ", ");
        print_member("type", k.type, ", ");
        print_member("range", k.range, ", ");
        print_member("unit", k.unit, ", ");
        print_member("default", k.default_value, ", ");
        print_member("doc", k.doc, i + 1 < n ? "},\n" : "}\n");
    }
    printf("]\n");
    return TD_EXIT_OK;
}

/* housing body: the housing on its mounts, when it has them. */
static void print_housing_body(const td_model *m)
{
    td_housing_body b;
    int i;
    if (!td_model_get_housing_body(m, &b))
        return;
    printf("housing      a body of %.6g kg, %.6g kg m^2 about z = %.6g m (%s), on %d mount%s:", b.mass, b.inertia,
           b.centre, b.inertia > 0.0 ? "tilting" : "translating", b.mount_count, b.mount_count > 1 ? "s" : "");
    for (i = 0; i < b.mount_count; i++)
        printf("%s z %.6g m: k %.6g N/m, c %.6g N s/m", i > 0 ? ";" : "", b.mounts[i].position, b.mounts[i].stiffness,
               b.mounts[i].damping);
    printf("\n");
}

/* 1 if a controller of m is a plug-in (no linear law for the modes). */
static int has_plugin(const td_model *m)
{
    int i;
    for (i = 0; i < td_model_controller_count(m); i++)
        if (td_model_get_plugin(m, i))
            return 1;
    return 0;
}

static int print_modes(const td_model *m, const td_modal_options *opt, int count)
{
    td_system *sys = NULL;
    td_modal *modes = NULL;
    td_error err;
    double gx, gy;
    if (td_system_create(m, &sys, &err) != TD_OK) {
        fprintf(stderr, "touchdown info: %s\n", err.message);
        return TD_EXIT_USAGE;
    }
    td_model_gravity(m, &gx, &gy);
    print_speed(m);
    printf("gravity      %s\n", (gx != 0.0 || gy != 0.0) ? "on" : "off");
    print_housing_body(m);
    printf("DOFs         %d mechanical (%s%s), %d first-order states with the AMB lags\n", td_system_dof_count(sys),
           td_system_is_reduced(sys) ? "reduced" : "4 per node",
           td_model_housing_body_dofs(m) == 4   ? " + 4 of the housing body"
           : td_model_housing_body_dofs(m) == 2 ? " + 2 of the housing body"
                                                : "",
           td_modal_state_count(sys));
    td_print_reduction(stdout, sys);
    if (td_modal_solve_lowest(sys, td_model_speed(m), count, &modes, &err) != TD_OK) {
        int plugin = has_plugin(m); /* the analysis refuses a plug-in's law: a fact of the case, said */
        if (plugin)
            printf("modes        not computed: %s\n", err.message);
        else
            fprintf(stderr, "touchdown info: %s\n", err.message);
        td_system_free(&sys);
        return plugin ? TD_EXIT_OK : TD_EXIT_FAILED;
    }
    if (td_modal_computed_count(modes) < td_modal_state_count(sys))
        printf("stability    %s among the %d roots nearest 0 (of %d; a large model's roots are not all computed)\n",
               td_stability_word(modes), td_modal_computed_count(modes), td_modal_state_count(sys));
    else
        printf("stability    %s\n", td_stability_word(modes));
    printf("first modes at the case speed:\n");
    td_print_modes(stdout, modes, count, 10);
    if (td_system_is_reduced(sys))
        td_print_reduction_error(stdout, sys, td_model_speed(m), opt->response_speeds, opt->response_speed_count);
    td_modal_free(&modes);
    td_system_free(&sys);
    return TD_EXIT_OK;
}

int td_cmd_info(int argc, char **argv)
{
    static const struct option longopts[] = {{"set", required_argument, NULL, 's'},
                                             {"modes", required_argument, NULL, 'n'},
                                             {"keys", no_argument, NULL, 'k'},
                                             {"help", no_argument, NULL, 'h'},
                                             {NULL, 0, NULL, 0}};
    td_cli_sets sets = {{0}, 0};
    td_case *c = NULL;
    int opt, code, count = 6, keys = 0;
    char *end;

    optind = 1;
    while ((opt = getopt_long(argc, argv, "s:n:h", longopts, NULL)) != -1) {
        switch (opt) {
        case 's':
            if (td_cli_add_set(&sets, optarg))
                return TD_EXIT_USAGE;
            break;
        case 'n':
            count = (int)strtol(optarg, &end, 10);
            if (*end || count < 1) {
                td_cli_error("info", "--modes wants a positive whole number, not '%s'", optarg);
                return TD_EXIT_USAGE;
            }
            break;
        case 'k': keys = 1; break;
        case 'h': fputs(info_usage, stdout); return TD_EXIT_OK;
        default: fputs(info_usage, stderr); return TD_EXIT_USAGE;
        }
    }
    if (keys && optind == argc)
        return print_keys();
    if (keys) {
        td_cli_error("info", "--keys lists the keys every case may use: give it no case file");
        return TD_EXIT_USAGE;
    }
    if (optind != argc - 1) {
        td_cli_error("info", "expected exactly one case file (see touchdown info --help)");
        return TD_EXIT_USAGE;
    }
    if ((code = td_cli_load_case(argv[optind], &sets, &c)))
        return code;
    printf("case         %s (%s)\n", td_case_name(c), td_case_path(c));
    if (td_case_description(c)[0])
        printf("description  %s\n", td_case_description(c));
    print_parts(td_case_model(c));
    td_print_controllers(stdout, c);
    td_print_recovery(stdout, td_case_model(c));
    code = print_modes(td_case_model(c), td_case_modal_options(c), count);
    td_case_free(&c);
    return code;
}
