/* The one test of an undefined value (touchdown/dofs.h, "Undefined values"). */
#include "touchdown/dofs.h"

int td_is_undefined(double x)
{
    return isnan(x) != 0;
}
