/*
 * touchdown/touchdown.h - umbrella header: everything a program linking libtouchdown needs.
 */
#ifndef TOUCHDOWN_TOUCHDOWN_H
#define TOUCHDOWN_TOUCHDOWN_H

#include "touchdown/assess.h"
#include "touchdown/case.h"
#include "touchdown/controller.h"
#include "touchdown/dofs.h"
#include "touchdown/error.h"
#include "touchdown/fmu.h"
#include "touchdown/housing.h"
#include "touchdown/job.h"
#include "touchdown/json.h"
#include "touchdown/modal.h"
#include "touchdown/modal_output.h"
#include "touchdown/model.h"
#include "touchdown/options.h"
#include "touchdown/output.h"
#include "touchdown/records.h"
#include "touchdown/result.h"
#include "touchdown/run.h"
#include "touchdown/sim.h"
#include "touchdown/sweep.h"
#include "touchdown/system.h"
#include "touchdown/version.h"

#endif /* TOUCHDOWN_TOUCHDOWN_H */
