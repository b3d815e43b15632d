/* Stub of the e-puck2 firmware's src/motors.h (FW2 d2e0dbba): the declarations the kit uses. */
#ifndef MOTORS_H
#define MOTORS_H

#include <stdint.h>

#define MOTOR_SPEED_LIMIT 1100 // [step/s]

void left_motor_set_speed(int speed);
void right_motor_set_speed(int speed);
int32_t left_motor_get_pos(void);
int32_t right_motor_get_pos(void);
void motors_init(void);

#endif /* MOTORS_H */
