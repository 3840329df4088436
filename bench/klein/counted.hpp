// One out-of-line function per operation and side, with C names, so that scripts/bench-klein.sh can count the
// instructions the compiler emitted for each (objdump --disassemble=kb_...). The checks of main.cpp call these
// same functions, so the counted code is the checked code. The timed loops call the libraries inline.
#pragma once

#include "convert.hpp"

#define KB_COUNTED extern "C" __attribute__((noinline))

KB_COUNTED void kb_klein_gp_rotor_rotor(const kln::rotor* a, const kln::rotor* b, kln::rotor* r);
KB_COUNTED void kb_cgagen_gp_rotor_rotor(const pga3::rotor* a, const pga3::rotor* b, pga3::rotor* r);
KB_COUNTED void kb_klein_gp_motor_motor(const kln::motor* a, const kln::motor* b, kln::motor* r);
KB_COUNTED void kb_cgagen_gp_motor_motor(const pga3::motor* a, const pga3::motor* b, pga3::motor* r);
KB_COUNTED void kb_klein_sandwich_motor_point(const kln::motor* m, const kln::point* x, kln::point* r);
KB_COUNTED void kb_cgagen_sandwich_motor_point(const pga3::motor* m, const pga3::point* x, pga3::point* r);
KB_COUNTED void kb_klein_sandwich_motor_line(const kln::motor* m, const kln::line* x, kln::line* r);
KB_COUNTED void kb_cgagen_sandwich_motor_line(const pga3::motor* m, const pga3::line* x, pga3::line* r);
KB_COUNTED void kb_klein_sandwich_motor_plane(const kln::motor* m, const kln::plane* x, kln::plane* r);
KB_COUNTED void kb_cgagen_sandwich_motor_plane(const pga3::motor* m, const pga3::plane* x, pga3::plane* r);
KB_COUNTED void kb_klein_motor_to_mat3x4(const kln::motor* m, kln::mat3x4* r);
KB_COUNTED void kb_cgagen_motor_to_matrix(const pga3::motor* m, pga3::matrix_t<float, pga3::point_t, pga3::point_t>* r);
KB_COUNTED void kb_klein_exp_line(const kln::line* l, kln::motor* r);
KB_COUNTED void kb_cgagen_exp_line(const pga3::line* l, pga3::motor* r);
KB_COUNTED void kb_klein_log_motor(const kln::motor* m, kln::line* r);
KB_COUNTED void kb_cgagen_log_motor(const pga3::motor* m, pga3::line* r);
