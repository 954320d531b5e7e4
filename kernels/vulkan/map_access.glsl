// Shared by the trnkit compute shaders: reading 8-bit pixels packed four to a 32-bit word (so no
// 8-bit storage extension is needed) and the bilinear formula of scoring.hpp, evaluated without
// fused multiply-add (`precise`) so that every backend gets bit-identical values.
#ifndef TRN_MAP_ACCESS_GLSL
#define TRN_MAP_ACCESS_GLSL

// Byte `index` of a word array, as an unsigned value 0..255.
#define TRN_BYTE_OF(words, index) (((words)[(index) >> 2u] >> (((index) & 3u) * 8u)) & 0xFFu)

// top = m00 + fx*(m10-m00); bot = m01 + fx*(m11-m01); value = top + fy*(bot-top)
float trn_bilinear(float m00, float m10, float m01, float m11, float fx, float fy) {
    precise float top = m00 + fx * (m10 - m00);
    precise float bot = m01 + fx * (m11 - m01);
    precise float value = top + fy * (bot - top);
    return value;
}

#endif
