// LDR-FLIP's constants shared by the CPU oracle (harness/metrics/flip.h), the config's default and
// the GPU pass (shaders/flip_*.comp).
#ifndef LB_FLIP_PARAMS_H
#define LB_FLIP_PARAMS_H

// The paper's viewing condition: a 0.7 m wide 3840-pixel display seen from 0.7 m,
// 3840 / 0.7 x 0.7 x pi / 180 pixels per degree.
#define LB_FLIP_DEFAULT_PPD 67.0206432300439

#endif
