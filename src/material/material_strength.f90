!> Deviatoric stress kernels: hypoelastic update with the Jaumann rate and
!> radial return to the von Mises yield surface (elastic-perfectly plastic, or
!> with linear isotropic hardening Y = Y0 + H eps_p).
!> Plain arrays, no MPI, no I/O. Stress components: xx, yy, zz, xy, yz, zx.
module material_strength
  use core_kinds, only: rk
  implicit none
  private
  public :: deviatoric_update, velocity_gradient, equivalent_strain_rate

contains

  !> Velocity gradient of a zone, the exact volume average of grad v:
  !> grad_ij = (1/V) sum_k v_i,k dV/dx_j,k.
  pure subroutine velocity_gradient(v, b, volume, grad)
    real(rk), intent(in) :: v(3, 8) !< node velocities
    real(rk), intent(in) :: b(3, 8) !< dV/dx of each node
    real(rk), intent(in) :: volume
    real(rk), intent(out) :: grad(3, 3) !< grad(i, j) = d v_i / d x_j
    integer :: k, i, j
    grad = 0.0_rk
    do k = 1, 8
      do j = 1, 3
        do i = 1, 3
          grad(i, j) = grad(i, j) + v(i, k) * b(j, k)
        end do
      end do
    end do
    grad = grad / volume
  end subroutine velocity_gradient

  !> s_new = radial_return(s + step (2 G D' + W s - s W), Y): trial stress by the
  !> Jaumann rate, scaled back to the yield surface sqrt(3/2 s:s) = Y when
  !> outside it. Returns the equivalent plastic strain increment
  !> (sbar_trial - Y) / (3 G). With a linear hardening modulus H the surface
  !> grows with the increment: sbar_new = Y + H dplastic = sbar_trial - 3 G dplastic,
  !> so dplastic = (sbar_trial - Y) / (3 G + H) and s_new is scaled to Y + H dplastic
  !> (exact for linear hardening; H = 0 is the perfectly plastic return, bit for bit).
  pure subroutine deviatoric_update(s, grad, step, shear, yield, s_new, dplastic, hardening)
    real(rk), intent(in) :: s(6) !< deviatoric stress at the start of the step
    real(rk), intent(in) :: grad(3, 3) !< velocity gradient over the step
    real(rk), intent(in) :: step !< time step
    real(rk), intent(in) :: shear !< shear modulus G
    real(rk), intent(in) :: yield !< yield stress Y at the start of the step (huge for elastic)
    real(rk), intent(out) :: s_new(6)
    real(rk), intent(out) :: dplastic
    real(rk), intent(in), optional :: hardening !< linear hardening modulus H >= 0 (default 0)
    real(rk) :: d(3, 3), w(3, 3), sm(3, 3), rate(3, 3), trace, sbar, h
    ! A melted (or strengthless) zone carries no deviatoric stress.
    if (.not. (shear > 0.0_rk) .or. .not. (yield > 0.0_rk)) then
      s_new = 0.0_rk
      dplastic = 0.0_rk
      return
    end if
    d = 0.5_rk * (grad + transpose(grad))
    w = 0.5_rk * (grad - transpose(grad))
    trace = (d(1, 1) + d(2, 2) + d(3, 3)) / 3.0_rk
    d(1, 1) = d(1, 1) - trace
    d(2, 2) = d(2, 2) - trace
    d(3, 3) = d(3, 3) - trace
    sm = reshape([s(1), s(4), s(6), s(4), s(2), s(5), s(6), s(5), s(3)], [3, 3])
    rate = 2.0_rk * shear * d + matmul(w, sm) - matmul(sm, w)
    sm = sm + step * rate
    ! Keep it deviatoric (the rotation terms are traceless only to round-off).
    trace = (sm(1, 1) + sm(2, 2) + sm(3, 3)) / 3.0_rk
    s_new = [sm(1, 1) - trace, sm(2, 2) - trace, sm(3, 3) - trace, &
        0.5_rk * (sm(1, 2) + sm(2, 1)), 0.5_rk * (sm(2, 3) + sm(3, 2)), &
        0.5_rk * (sm(3, 1) + sm(1, 3))]
    sbar = sqrt(1.5_rk * (s_new(1)**2 + s_new(2)**2 + s_new(3)**2 &
        + 2.0_rk * (s_new(4)**2 + s_new(5)**2 + s_new(6)**2)))
    dplastic = 0.0_rk
    if (sbar > yield) then
      h = 0.0_rk
      if (present(hardening)) h = hardening
      if (h > 0.0_rk) then
        dplastic = (sbar - yield) / (3.0_rk * shear + h)
        s_new = s_new * ((yield + h * dplastic) / sbar)
      else
        s_new = s_new * (yield / sbar)
        dplastic = (sbar - yield) / (3.0_rk * shear)
      end if
    end if
  end subroutine deviatoric_update

  !> Equivalent (von Mises) deviatoric strain rate sqrt(2/3 D':D').
  pure function equivalent_strain_rate(grad) result(rate)
    real(rk), intent(in) :: grad(3, 3)
    real(rk) :: rate
    real(rk) :: d(3, 3), trace
    d = 0.5_rk * (grad + transpose(grad))
    trace = (d(1, 1) + d(2, 2) + d(3, 3)) / 3.0_rk
    d(1, 1) = d(1, 1) - trace
    d(2, 2) = d(2, 2) - trace
    d(3, 3) = d(3, 3) - trace
    rate = sqrt(2.0_rk / 3.0_rk * sum(d * d))
  end function equivalent_strain_rate

end module material_strength
