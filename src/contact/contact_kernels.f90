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
module contact_kernels
  use core_kinds, only: rk
  implicit none
  private
  public :: dlm_pair_force, dam_merged_normal_velocity, dam_put_back_velocity

  integer, parameter, public :: KERNEL_COORDINATE = 1, KERNEL_VELOCITY = 2, KERNEL_COMBINED = 3

contains

  !> DLM force of one facet pair on its hitting side along the normal, and
  !> whether the pair is gated (see the module notes).
  pure subroutine dlm_pair_force(form, mh, md, fh_n, fd_n, w, pen, gate, dt, target, fh, &
      gated)
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
    real(rk) :: mu, pen_free, goal
    mu = mh * md / (mh + md)
    pen_free = gate + dt * w + 0.5_rk * dt * dt * (fh_n / mh - fd_n / md)
    gated = pen_free > 0.0_rk .or. form == KERNEL_COORDINATE
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

end module contact_kernels
