/* The td_model record, visible inside the library only. */
#ifndef TD_MODEL_INTERNAL_H
#define TD_MODEL_INTERNAL_H

#include "touchdown/model.h"

/* A growable array of one part type. */
#define TD_PART_ARRAY(type)                                                                                            \
    struct {                                                                                                           \
        type *items;                                                                                                   \
        int count;                                                                                                     \
        int capacity;                                                                                                  \
    }

struct td_model {
    td_shaft_options shaft;
    TD_PART_ARRAY(td_shaft_element) elements;
    TD_PART_ARRAY(td_disc) discs; /* point masses are discs with Ip = Id = 0 */
    TD_PART_ARRAY(td_amb) ambs;
    TD_PART_ARRAY(td_bearing) bearings;
    TD_PART_ARRAY(td_retainer) retainers;
    TD_PART_ARRAY(td_unbalance) unbalances;
    TD_PART_ARRAY(td_change) changes;           /* kept sorted by time (stable) */
    TD_PART_ARRAY(int) change_entries;          /* change i was the change_entries.items[i]-th added */
    double speed;                               /* rad/s */
    TD_PART_ARRAY(td_speed_point) speed_points; /* the ramp, increasing times */
    td_spin spin;
    double gravity[2];       /* m/s^2 */
    double reduction_cutoff; /* Hz: Craig-Bampton reduction of the system (lib/model/reduce.c); 0: full model */
};

#endif
