!> The pointwise formulas of the two contact methods, apart from the pair
!> bookkeeping and the parallel sums of contact_enforce, so that they can be
!> tested on hand-computable cases (tests/unit/test_contact_kernels.f90).
!> Pure, no state.
!>
!> DLM, one facet pair seen as two lumped masses along the pair's normal n:
!> the hitting share mh (its node's mass times its share wh), the target
!> share md, the hydro forces along n fh_n, fd_n (shares of the node forces),
!> the approach speed w = (vh - vd) . n and the penetration pen (> 0:
!> overlap). With mu = mh md / (mh + md), the pair force on the hitting side
!> (along n; <= 0 pushes it back) is
!>   coordinate: mu (fd_n/md - fh_n/mh - w/(dt/2) - pen/(dt^2/2)): the gap of
!>               the two masses closed exactly at t + dt under
!>               x' = x + v dt + a dt^2/2 (the seed paper's eq. 20);
!>   velocity:   mu (fd_n/md - fh_n/mh + (target - w)/dt), target the
!>               separating speed of the recovery (0 without): the approach
!>               speed at t + dt is the target;
!>   combined:   the velocity form with target -max(pen + dt w/2, 0)/dt;
!> and only while the pair is gated: the free motion would close the gap at
!> t + dt, gate + dt w + dt^2/2 (fh_n/mh - fd_n/md) > 0 (gate: the
!> penetration at the overlap's deepest vertex); the coordinate form always.
!> Contact only pushes: the force is min(., 0).
!>
!> DAM, the master matching: a master node's normal velocity at t + dt is
!> the one of the merged body of itself and its slave shares, (p + dt f) . n
!> / m with the masses m, momenta p and forces f summed over the node and
!> the shares; then the put-back: the slave's normal velocity becomes the
!> master's interpolated one, its tangential velocity is kept.
!>
!> Coulomb friction (coefficient cf > 0; with cf = 0 the callers skip it):
!> the tangential impulse that would stop the relative tangential velocity
!> over the step (stick), scaled down to cf times the normal impulse when it
!> is larger (slip), so directed against the relative tangential velocity.
!>   DLM, per facet pair: with the free relative velocity at t + dt,
!>   vr = (vh + dt fh/mh) - (vd + dt fd/md) (fh, fd the pair's shares of the
!>   hydro node forces, full vectors) and its part vt normal to n, the
!>   tangential force on the hitting side is -mu vt/dt (mu = mh md/(mh + md),
!>   the same lumped masses as the normal force), at most cf |fn| in size (fn
!>   the pair's normal force); the target side gets its opposite.
!>   DAM, at the put-back: the slave's velocity change relative to the
!>   master's interpolated velocity, tangential part, -vt, at most cf |dvn|
!>   in size (dvn the put-back's change of the slave's normal velocity: the
!>   normal impulse per unit mass); contact_enforce gives the masters the
!>   opposite momentum.
module contact_kernels
  use core_kinds, only: rk
  implicit none
  private
  public :: dlm_pair_force, dam_merged_normal_velocity, dam_put_back_velocity
  public :: coulomb_limit, dlm_pair_friction, dam_friction_velocity

  integer, parameter, public :: KERNEL_COORDINATE = 1, KERNEL_VELOCITY = 2, KERNEL_COMBINED = 3

contains

  !> DLM force of one facet pair on its hitting side along the normal, and
  !> whether the pair is gated (see the module notes).
  pure subroutine dlm_pair_force(form, mh, md, fh_n, fd_n, w, pen, gate, dt, target, fh, &
      gated, gate_open)
    integer, intent(in) :: form !< KERNEL_COORDINATE, KERNEL_VELOCITY or KERNEL_COMBINED
    real(rk), intent(in) :: mh, md !< lumped masses of the two sides
    real(rk), intent(in) :: fh_n, fd_n !< their hydro forces along the normal
    real(rk), intent(in) :: w !< approach speed (vh - vd) . n
    real(rk), intent(in) :: pen !< penetration at the overlap centroid (> 0: overlap)
    real(rk), intent(in) :: gate !< penetration at the overlap's deepest vertex
    real(rk), intent(in) :: dt !< the stage's step
    real(rk), intent(in) :: target !< velocity form: approach speed wanted at t + dt (<= 0)
    real(rk), intent(out) :: fh
    logical, intent(out) :: gated
    !> the gate decided already (with the pair's raw shares; the gate does
    !> not depend on them but for round-off), so that it is the one counted
    logical, intent(in), optional :: gate_open
    real(rk) :: mu, pen_free, goal
    mu = mh * md / (mh + md)
    if (present(gate_open)) then
      gated = gate_open .or. form == KERNEL_COORDINATE
    else
      pen_free = gate + dt * w + 0.5_rk * dt * dt * (fh_n / mh - fd_n / md)
      gated = pen_free > 0.0_rk .or. form == KERNEL_COORDINATE
    end if
    fh = 0.0_rk
    select case (form)
    case (KERNEL_COORDINATE)
      fh = mu * (fd_n / md - fh_n / mh - w / (0.5_rk * dt) - pen / (0.5_rk * dt * dt))
    case (KERNEL_VELOCITY)
      if (gated) fh = mu * (fd_n / md - fh_n / mh + (target - w) / dt)
    case default
      if (gated) then
        goal = -max(pen + 0.5_rk * dt * w, 0.0_rk) / dt
        fh = mu * (fd_n / md - fh_n / mh + (goal - w) / dt)
      end if
    end select
    fh = min(fh, 0.0_rk)
  end subroutine dlm_pair_force

  !> DAM: the normal velocity at t + dt of a master node merged with its
  !> slave shares: summed mass m, momentum p and force f.
  pure real(rk) function dam_merged_normal_velocity(m, p, f, unit, dt) result(vn)
    real(rk), intent(in) :: m, p(3), f(3), unit(3), dt
    vn = dot_product(p + dt * f, unit) / m
  end function dam_merged_normal_velocity

  !> DAM put-back: the slave's velocity vs with its component along nrm
  !> replaced by target.
  pure function dam_put_back_velocity(vs, nrm, target) result(v)
    real(rk), intent(in) :: vs(3), nrm(3), target
    real(rk) :: v(3)
    v = vs + (target - dot_product(vs, nrm)) * nrm
  end function dam_put_back_velocity

  !> Coulomb law: the stick value (impulse, force or velocity change) if its
  !> size is within limit (>= 0), else scaled down to size limit (slip).
  pure function coulomb_limit(stick, limit) result(t)
    real(rk), intent(in) :: stick(3), limit
    real(rk) :: t(3), size
    size = norm2(stick)
    if (size > limit) then
      t = (limit / size) * stick
    else
      t = stick
    end if
  end function coulomb_limit

  !> DLM: the tangential friction force of one facet pair on its hitting side
  !> (the target side gets -ft); see the module notes.
  pure function dlm_pair_friction(cf, mh, md, vh, vd, fh, fd, nrm, dt, fn) result(ft)
    real(rk), intent(in) :: cf !< Coulomb coefficient
    real(rk), intent(in) :: mh, md !< lumped masses of the two sides
    real(rk), intent(in) :: vh(3), vd(3) !< their velocities at t
    real(rk), intent(in) :: fh(3), fd(3) !< their shares of the hydro forces
    real(rk), intent(in) :: nrm(3) !< the pair's unit normal
    real(rk), intent(in) :: dt !< the stage's step
    real(rk), intent(in) :: fn !< the pair's normal force on the hitting side (<= 0)
    real(rk) :: ft(3), vr(3), vt(3)
    vr = (vh + dt * fh / mh) - (vd + dt * fd / md)
    vt = vr - dot_product(vr, nrm) * nrm
    ft = coulomb_limit(-(mh * md / (mh + md)) * vt / dt, cf * abs(fn))
  end function dlm_pair_friction

  !> DAM: the friction change of a put-back slave's velocity vs (after the
  !> normal put-back) relative to the master's interpolated velocity vm;
  !> dvn: the put-back's change of the slave's normal velocity.
  pure function dam_friction_velocity(cf, vs, vm, nrm, dvn) result(dv)
    real(rk), intent(in) :: cf, vs(3), vm(3), nrm(3), dvn
    real(rk) :: dv(3), vr(3)
    vr = vs - vm
    dv = coulomb_limit(-(vr - dot_product(vr, nrm) * nrm), cf * abs(dvn))
  end function dam_friction_velocity

end module contact_kernels
