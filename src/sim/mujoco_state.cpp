#include "sim/mujoco_state.hpp"

#include <mujoco/mujoco.h>

#include <cstring>

namespace mimic {

void reset_state(const mjModel* m, mjData* d) {
  d->pstack = 0;
  d->maxuse_stack = d->maxuse_con = d->maxuse_efc = 0;
  std::memset(d->warning, 0, sizeof(d->warning));
  std::memset(d->timer, 0, sizeof(d->timer));
  std::memset(d->solver, 0, sizeof(d->solver));
  d->solver_iter = d->solver_nnz = 0;
  mju_zero(d->solver_fwdinv, 2);
  d->ne = d->nf = d->nefc = d->ncon = 0;
  d->time = 0;
  mju_zero(d->energy, 2);

  mju_copy(d->qpos, m->qpos0, m->nq);
  mju_zero(d->qvel, m->nv);
  mju_zero(d->act, m->na);
  mju_zero(d->ctrl, m->nu);
  mju_zero(d->qfrc_applied, m->nv);
  mju_zero(d->xfrc_applied, 6 * m->nbody);
  mju_zero(d->qacc, m->nv);
  mju_zero(d->qacc_warmstart, m->nv);
  mju_zero(d->act_dot, m->na);
  mju_zero(d->userdata, m->nuserdata);
  mju_zero(d->sensordata, m->nsensordata);
  for (int b = 0; b < m->nbody; ++b) {  // every mocap pose belongs to one body: its pose in the model
    const int id = m->body_mocapid[b];
    if (id < 0) continue;
    mju_copy3(d->mocap_pos + 3 * id, m->body_pos + 3 * b);
    mju_copy4(d->mocap_quat + 4 * id, m->body_quat + 4 * b);
  }
}

}  // namespace mimic
