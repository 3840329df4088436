// The out-of-line operations of counted.hpp: each is the library's own call and nothing else.
#include "counted.hpp"

void kb_klein_gp_rotor_rotor(const kln::rotor* a, const kln::rotor* b, kln::rotor* r) { *r = *a * *b; }
void kb_cgagen_gp_rotor_rotor(const pga3::rotor* a, const pga3::rotor* b, pga3::rotor* r) { *r = pga3::gp(*a, *b); }
void kb_klein_gp_motor_motor(const kln::motor* a, const kln::motor* b, kln::motor* r) { *r = *a * *b; }
void kb_cgagen_gp_motor_motor(const pga3::motor* a, const pga3::motor* b, pga3::motor* r) { *r = pga3::gp(*a, *b); }

void kb_klein_sandwich_motor_point(const kln::motor* m, const kln::point* x, kln::point* r) { *r = (*m)(*x); }
void kb_cgagen_sandwich_motor_point(const pga3::motor* m, const pga3::point* x, pga3::point* r) {
  *r = pga3::sandwich(*m, *x);
}
void kb_klein_sandwich_motor_line(const kln::motor* m, const kln::line* x, kln::line* r) { *r = (*m)(*x); }
void kb_cgagen_sandwich_motor_line(const pga3::motor* m, const pga3::line* x, pga3::line* r) {
  *r = pga3::sandwich(*m, *x);
}
void kb_klein_sandwich_motor_plane(const kln::motor* m, const kln::plane* x, kln::plane* r) { *r = (*m)(*x); }
void kb_cgagen_sandwich_motor_plane(const pga3::motor* m, const pga3::plane* x, pga3::plane* r) {
  *r = pga3::sandwich(*m, *x);
}

void kb_klein_motor_to_mat3x4(const kln::motor* m, kln::mat3x4* r) { *r = m->as_mat3x4(); }
void kb_cgagen_motor_to_matrix(const pga3::motor* m, pga3::matrix_t<float, pga3::point_t, pga3::point_t>* r) {
  *r = pga3::matrix(*m, pga3::of<pga3::point_t>);
}

void kb_klein_exp_line(const kln::line* l, kln::motor* r) { *r = kln::exp(*l); }
void kb_cgagen_exp_line(const pga3::line* l, pga3::motor* r) { *r = pga3::exp(*l); }
void kb_klein_log_motor(const kln::motor* m, kln::line* r) { *r = kln::log(*m); }
void kb_cgagen_log_motor(const pga3::motor* m, pga3::line* r) { *r = pga3::log(*m); }
