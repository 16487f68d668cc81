// unity_config.h -- Unity's configuration in the Cortex-M test images (tests/target):
// every character of Unity's output goes to sva_target_putchar(), which sends it over
// Arm semihosting a line at a time (target_io.c). Included by Unity through
// UNITY_INCLUDE_CONFIG_H, which the image build defines for Unity and the tests.
#ifndef SVA_TARGET_UNITY_CONFIG_H
#define SVA_TARGET_UNITY_CONFIG_H

void sva_target_putchar(int c);
void sva_target_flush(void);

#define UNITY_OUTPUT_CHAR(c) sva_target_putchar(c)
#define UNITY_OUTPUT_FLUSH() sva_target_flush()

#endif
