/* The compiled vector operations (lib/sim/sim_nvector.c) against SUNDIALS's own serial vector:
 * every operation IDA can call, on odd and even lengths, with aliased arguments, must give the
 * serial vector's result (to a few ulps where the summation order differs). */
#include "td_test.h"

#include "sim/sim_internal.h"

#include <math.h>
#include <stdlib.h>

#define NV 4

typedef struct pair {
    N_Vector a[NV]; /* SUNDIALS's serial operations */
    N_Vector b[NV]; /* the library's, same contents */
    N_Vector id_a, id_b;
    int n;
} pair;

static double value(int i, int k)
{
    return sin(0.7 * i + 1.3 * k + 0.2) * (1.0 + k) + (i % 5 == 0 ? 0.0 : 0.01 * k);
}

static pair make_pair(SUNContext ctx, int n)
{
    pair p;
    N_Vector ta = N_VNew_Serial(n, ctx), tb = N_VNew_Serial(n, ctx);
    int k, i;
    assert_non_null(ta);
    assert_non_null(tb);
    td_sim_nvector_optimize(tb);
    p.n = n;
    for (k = 0; k < NV; k++) {
        p.a[k] = N_VClone(ta);
        p.b[k] = N_VClone(tb); /* the clone must inherit the operations */
        for (i = 0; i < n; i++)
            NV_Ith_S(p.a[k], i) = NV_Ith_S(p.b[k], i) = value(i, k);
    }
    p.id_a = N_VClone(ta);
    p.id_b = N_VClone(tb);
    for (i = 0; i < n; i++)
        NV_Ith_S(p.id_a, i) = NV_Ith_S(p.id_b, i) = (i % 3 == 1) ? 0.0 : 1.0;
    N_VDestroy(ta);
    N_VDestroy(tb);
    return p;
}

static void free_pair(pair *p)
{
    int k;
    for (k = 0; k < NV; k++) {
        N_VDestroy(p->a[k]);
        N_VDestroy(p->b[k]);
    }
    N_VDestroy(p->id_a);
    N_VDestroy(p->id_b);
}

/* Every vector of the pair equal elementwise to rounding (1e-15 relative + 1e-300). */
static void assert_same(const pair *p)
{
    int k, i;
    for (k = 0; k < NV; k++)
        for (i = 0; i < p->n; i++)
            assert_close(NV_Ith_S(p->b[k], i), NV_Ith_S(p->a[k], i), 1e-15, 1e-300);
}

static void test_operations(void **state)
{
    SUNContext ctx;
    static const int lengths[3] = {1, 36, 37};
    int li;
    (void)state;
    assert_int_equal(td_sun_context_create(&ctx), 0);
    for (li = 0; li < 3; li++) {
        pair p = make_pair(ctx, lengths[li]);
        sunrealtype c3[3] = {0.5, -1.25, 2.0}, c4[4] = {1.0, -0.5, 0.25, 3.0}, ra[NV], rb[NV];
        N_Vector *A = p.a, *B = p.b;
        N_Vector Ya[2] = {A[1], A[2]}, Yb[2] = {B[1], B[2]}, Za[2] = {A[2], A[3]}, Zb[2] = {B[2], B[3]};
        int k;

        assert_ptr_equal(B[0]->ops->nvlinearsum, B[3]->ops->nvlinearsum);
        assert_true(B[0]->ops->nvlinearsum != A[0]->ops->nvlinearsum);
        assert_int_equal(N_VGetVectorID(B[0]), SUNDIALS_NVEC_SERIAL);

        /* single operations, including aliased outputs */
        N_VLinearSum(0.3, A[0], -1.7, A[1], A[2]), N_VLinearSum(0.3, B[0], -1.7, B[1], B[2]);
        N_VLinearSum(1.0, A[2], 2.0, A[1], A[2]), N_VLinearSum(1.0, B[2], 2.0, B[1], B[2]);
        N_VLinearSum(-1.0, A[1], 1.0, A[3], A[1]), N_VLinearSum(-1.0, B[1], 1.0, B[3], B[1]);
        assert_same(&p);
        N_VScale(-2.5, A[0], A[3]), N_VScale(-2.5, B[0], B[3]);
        N_VScale(0.5, A[3], A[3]), N_VScale(0.5, B[3], B[3]);
        N_VProd(A[0], A[1], A[2]), N_VProd(B[0], B[1], B[2]);
        N_VAbs(A[1], A[1]), N_VAbs(B[1], B[1]);
        N_VAddConst(A[1], 0.75, A[1]), N_VAddConst(B[1], 0.75, B[1]);
        N_VDiv(A[2], A[1], A[2]), N_VDiv(B[2], B[1], B[2]);
        N_VInv(A[1], A[3]), N_VInv(B[1], B[3]);
        assert_same(&p);
        assert_close(N_VDotProd(B[0], B[2]), N_VDotProd(A[0], A[2]), 1e-14, 1e-300);
        assert_close(N_VMaxNorm(B[2]), N_VMaxNorm(A[2]), 0.0, 0.0);
        assert_close(N_VWrmsNorm(B[0], B[1]), N_VWrmsNorm(A[0], A[1]), 1e-14, 0.0);
        assert_close(N_VWrmsNormMask(B[0], B[1], p.id_b), N_VWrmsNormMask(A[0], A[1], p.id_a), 1e-14, 0.0);
        assert_close(N_VWL2Norm(B[0], B[1]), N_VWL2Norm(A[0], A[1]), 1e-14, 0.0);
        assert_close(N_VL1Norm(B[0]), N_VL1Norm(A[0]), 1e-14, 0.0);
        assert_close(N_VMin(B[0]), N_VMin(A[0]), 0.0, 0.0);
        assert_close(N_VMinQuotient(B[0], B[1]), N_VMinQuotient(A[0], A[1]), 0.0, 0.0);
        N_VCompare(0.5, A[0], A[3]), N_VCompare(0.5, B[0], B[3]);
        assert_int_equal(N_VInvTest(B[0], B[2]), N_VInvTest(A[0], A[2]));
        N_VConst(0.0, p.id_a), N_VConst(0.0, p.id_b);
        assert_int_equal(N_VInvTest(p.id_b, B[1]), N_VInvTest(p.id_a, A[1])); /* all zero: false */
        N_VConst(-3.0, A[1]), N_VConst(-3.0, B[1]);
        assert_same(&p);

        /* fused and vector-array operations, with the output aliasing the first input */
        {
            int i;
            for (k = 0; k < NV; k++)
                for (i = 0; i < p.n; i++)
                    NV_Ith_S(A[k], i) = NV_Ith_S(B[k], i) = value(i, k + 7);
        }
        assert_int_equal(N_VLinearCombination(3, c3, A, A[3]), N_VLinearCombination(3, c3, B, B[3]));
        assert_int_equal(N_VLinearCombination(4, c4, A, A[0]), N_VLinearCombination(4, c4, B, B[0]));
        assert_int_equal(N_VLinearCombination(1, c4, A + 1, A[2]), N_VLinearCombination(1, c4, B + 1, B[2]));
        assert_same(&p);
        assert_int_equal(N_VScaleAddMulti(2, c3, A[0], Ya, Za), N_VScaleAddMulti(2, c3, B[0], Yb, Zb));
        assert_same(&p);
        assert_int_equal(N_VDotProdMulti(3, A[0], A + 1, ra), N_VDotProdMulti(3, B[0], B + 1, rb));
        for (k = 0; k < 3; k++)
            assert_close(rb[k], ra[k], 1e-14, 1e-300);
        assert_int_equal(N_VLinearSumVectorArray(2, 0.5, A, -2.0, A + 2, Za),
                         N_VLinearSumVectorArray(2, 0.5, B, -2.0, B + 2, Zb));
        assert_int_equal(N_VScaleVectorArray(2, c3, A, A), N_VScaleVectorArray(2, c3, B, B));
        assert_same(&p);
        assert_int_equal(N_VWrmsNormVectorArray(2, A, A + 2, ra), N_VWrmsNormVectorArray(2, B, B + 2, rb));
        for (k = 0; k < 2; k++)
            assert_close(rb[k], ra[k], 1e-14, 0.0);
        assert_int_equal(N_VConstVectorArray(2, 1.5, A + 1), N_VConstVectorArray(2, 1.5, B + 1));
        assert_same(&p);
        free_pair(&p);
    }
    SUNContext_Free(&ctx);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_operations),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
