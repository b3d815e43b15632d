/* Stub of the e-puck2 firmware's src/sensors/proximity.h (FW2 d2e0dbba): the declarations the
 * kit and its README use. */
#ifndef PROXIMITY_H
#define PROXIMITY_H

#include <stdint.h>

#define PROXIMITY_NB_CHANNELS 8
#define FAST_UPDATE 0 // Proximity sensors updated at 100 Hz

void proximity_start(uint8_t mode);
void calibrate_ir(void);
int get_prox(unsigned int sensor_number);
int get_calibrated_prox(unsigned int sensor_number);

#endif /* PROXIMITY_H */
