/* The list of models: adding one is a folder src/models/<model>/ and a line here (and its hb_model
 * value in include/hairbsdf.h). */
#include "model.h"

extern const hb_model_ops hb_deon_model, hb_marschner_model, hb_huang_model, hb_chiang_model;

static const hb_model_ops *const models[] = {
    [HB_MODEL_MARSCHNER] = &hb_marschner_model,
    [HB_MODEL_DEON] = &hb_deon_model,
    [HB_MODEL_HUANG] = &hb_huang_model,
    [HB_MODEL_CHIANG] = &hb_chiang_model,
};

const hb_model_ops *hb_model_ops_of(hb_model model)
{
    return (unsigned)model < sizeof models / sizeof models[0] ? models[model] : NULL;
}
