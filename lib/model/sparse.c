/*
 * The assembled matrices' one compressed form (system_internal.h): CXSparse triplets compressed,
 * duplicates summed, then transposed twice so that every column holds its row indices in
 * increasing order.
 */
#include "model/system_internal.h"

cs_di *td_system_compress(const cs_di *T)
{
    cs_di *A = cs_di_compress(T), *At;
    if (!A)
        return NULL;
    if (!cs_di_dupl(A)) {
        cs_di_spfree(A);
        return NULL;
    }
    At = cs_di_transpose(A, 1);
    cs_di_spfree(A);
    if (!At)
        return NULL;
    A = cs_di_transpose(At, 1);
    cs_di_spfree(At);
    return A;
}
