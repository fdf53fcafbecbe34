/* hb_hit_sample and hb_hit_eval_pdf: one hit's plain arrays as the vector calls' one-sample batch. */
#include "models/interface/plan.h"

hb_status hb_hit_sample(const hb_plan *plan, const float wo[3], const float *h, const float *u, float wi[3], float *pdf,
                        float weight[3])
{
    if (!wo || !u || !wi || !pdf || !weight)
        return hb_fail_null(__func__, !wo ? "wo" : !u ? "u" : !wi ? "wi" : !pdf ? "pdf" : "weight");
    const float *planes[HB_SAMPLE_DIMENSIONS] = { NULL }; /* u[d] as plane d, for the numbers the plan reads */
    int dimensions = plan ? hb_plan_sample_dimensions(plan) : 0;
    for (int d = 0; d < dimensions; d++)
        planes[d] = u + d;
    hb_sample_vectors_out out = { &wi[0], &wi[1], &wi[2], pdf, { &weight[0], &weight[1], &weight[2] } };
    if (h) {
        hb_sample_near_vectors_in in = { &wo[0], &wo[1], &wo[2], h, planes };
        return hb_sample_near_vectors(plan, 1, &in, &out, NULL);
    }
    hb_sample_vectors_in in = { &wo[0], &wo[1], &wo[2], planes };
    return hb_sample_vectors(plan, 1, &in, &out, NULL);
}

hb_status hb_hit_eval_pdf(const hb_plan *plan, const float wi[3], const float wo[3], const float *h, float f[3],
                          float *pdf)
{
    if (!wi || !wo || !f || !pdf)
        return hb_fail_null(__func__, !wi ? "wi" : !wo ? "wo" : !f ? "f" : "pdf");
    hb_rgb_soa rgb = { &f[0], &f[1], &f[2] };
    if (h)
        return hb_eval_pdf_near_vectors(plan, 1, (hb_near_vectors_soa){ &wi[0], &wi[1], &wi[2], &wo[0], &wo[1], &wo[2], h },
                                        rgb, pdf, NULL);
    return hb_eval_pdf_vectors(plan, 1, (hb_vectors_soa){ &wi[0], &wi[1], &wi[2], &wo[0], &wo[1], &wo[2] }, rgb, pdf, NULL);
}
