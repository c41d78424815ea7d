/* Small numeric constants and helpers shared inside the library. */
#ifndef TD_UTIL_NUMERIC_H
#define TD_UTIL_NUMERIC_H

#define TD_PI 3.14159265358979323846

#endif
