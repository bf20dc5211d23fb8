!> The contact methods' pointwise formulas (contact_kernels) on cases
!> computed by hand.
program test_contact_kernels
  use core_kinds, only: rk
  use check, only: check_true, check_close, check_summary
  use contact_kernels, only: dlm_pair_force, dam_merged_normal_velocity, &
      dam_put_back_velocity, KERNEL_COORDINATE, KERNEL_VELOCITY, KERNEL_COMBINED, &
      coulomb_limit, dlm_pair_friction, dam_friction_velocity
  implicit none
  real(rk) :: fh, mh, md, dt, w, vh, vd, pen, gap_end, fh_n, fd_n
  logical :: gated

  ! DLM, velocity form. Masses 2 and 6 (mu = 1.5), closing at w = 0.3 with
  ! no hydro force, touching (pen = 0), dt = 0.1: the force that stops the
  ! approach over the step is -mu w / dt = -4.5, and after it the two
  ! velocities are equal (momentum kept: -4.5 dt / 2 = -0.225 and
  ! +4.5 dt / 6 = +0.075 from vh = 0.3, vd = 0 give 0.075 both).
  mh = 2.0_rk
  md = 6.0_rk
  dt = 0.1_rk
  vh = 0.3_rk
  vd = 0.0_rk
  w = vh - vd
  call dlm_pair_force(KERNEL_VELOCITY, mh, md, 0.0_rk, 0.0_rk, w, 0.0_rk, 0.0_rk, dt, &
      0.0_rk, fh, gated)
  call check_true('DLM velocity: a closing pair is gated', gated)
  call check_close('DLM velocity: lambda = -mu w / dt = -4.5', fh, -4.5_rk, 1e-14_rk)
  call check_close('DLM velocity: approach stopped, vh'' = vd''', &
      (vh + dt * fh / mh) - (vd - dt * fh / md), 0.0_rk, 0.0_rk, 1e-15_rk)
  call check_close('DLM velocity: momentum kept', mh * (vh + dt * fh / mh) + &
      md * (vd - dt * fh / md), mh * vh + md * vd, 1e-15_rk)

  ! With hydro forces: the hitting side pushed on by 3, the target by -1
  ! (both toward each other): lambda = mu (fd/md - fh/mh - w/dt)
  ! = 1.5 (-1/6 - 3/2 - 3) = -7.
  call dlm_pair_force(KERNEL_VELOCITY, mh, md, 3.0_rk, -1.0_rk, w, 0.0_rk, 0.0_rk, dt, &
      0.0_rk, fh, gated)
  call check_close('DLM velocity with hydro forces: lambda = -7', fh, -7.0_rk, 1e-14_rk)

  ! Recovery target: a separating speed of -0.02 wanted: lambda =
  ! mu (-0.02 - 0.3) / dt = -4.8.
  call dlm_pair_force(KERNEL_VELOCITY, mh, md, 0.0_rk, 0.0_rk, w, 1.0e-3_rk, 1.0e-3_rk, dt, &
      -0.02_rk, fh, gated)
  call check_close('DLM velocity with a recovery target: lambda = -4.8', fh, -4.8_rk, 1e-14_rk)

  ! Separating (w = -0.3) from a gap of 0.01: not gated, no force.
  call dlm_pair_force(KERNEL_VELOCITY, mh, md, 0.0_rk, 0.0_rk, -0.3_rk, -0.01_rk, -0.01_rk, &
      dt, 0.0_rk, fh, gated)
  call check_true('DLM velocity: a separating pair is not gated and has no force', &
      .not. gated .and. fh == 0.0_rk)

  ! Gated (the free motion keeps a 0.2 overlap) but the hydro
  ! forces pull the two apart harder than the approach: the formula gives
  ! a positive (pulling) force, which contact never applies: fh = 0.
  call dlm_pair_force(KERNEL_VELOCITY, mh, md, -60.0_rk, 0.0_rk, 0.01_rk, 0.2_rk, 0.2_rk, &
      dt, 0.0_rk, fh, gated)
  call check_true('DLM velocity: gated, pulled apart: fh = min(fh, 0) = 0', gated .and. &
      fh == 0.0_rk)

  ! The coordinate form (the paper's eq. 20) closes the gap exactly: with
  ! pen = 0.002, w = 0.3, hydro forces 3 and -1, the relative position at
  ! t + dt under x' = x + v dt + a dt^2 / 2 is zero.
  pen = 0.002_rk
  fh_n = 3.0_rk
  fd_n = -1.0_rk
  call dlm_pair_force(KERNEL_COORDINATE, mh, md, fh_n, fd_n, w, pen, pen, dt, 0.0_rk, fh, &
      gated)
  gap_end = pen + dt * w + 0.5_rk * dt * dt * ((fh_n + fh) / mh - (fd_n - fh) / md)
  call check_close('DLM coordinate: the penetration at t + dt is 0', gap_end, 0.0_rk, 0.0_rk, &
      1e-15_rk)
  ! and a pair whose exact closure would pull is left alone: fh = 0.
  call dlm_pair_force(KERNEL_COORDINATE, mh, md, 0.0_rk, 0.0_rk, -0.3_rk, -0.05_rk, -0.05_rk, &
      dt, 0.0_rk, fh, gated)
  call check_true('DLM coordinate: an opening pair gets no (pulling) force', fh == 0.0_rk)

  ! Combined form: target -max(pen + dt w / 2, 0) / dt = -(0.002 + 0.015) / 0.1
  ! = -0.17; lambda = mu (target - w) / dt = 1.5 (-0.47) / 0.1 = -7.05.
  call dlm_pair_force(KERNEL_COMBINED, mh, md, 0.0_rk, 0.0_rk, w, pen, pen, dt, 0.0_rk, fh, &
      gated)
  call check_close('DLM combined: lambda = -7.05', fh, -7.05_rk, 1e-13_rk)

  ! DAM master matching: a master node (mass 1, velocity +2 along n, force
  ! 0) merged with slave shares of mass 3 moving at -1 along n and pushed
  ! by +6: (1 * 2 + 3 * (-1) + dt 6) / 4 at dt = 0.1 = -0.1.
  call check_close('DAM merged normal velocity = (p + dt f) . n / m = -0.1', &
      dam_merged_normal_velocity(4.0_rk, [0.0_rk, 0.0_rk, -1.0_rk], [0.0_rk, 0.0_rk, 6.0_rk], &
      [0.0_rk, 0.0_rk, 1.0_rk], 0.1_rk), -0.1_rk, 1e-14_rk)
  ! Oblique normal: the tangential momentum does not enter.
  call check_close('DAM merged normal velocity, oblique normal', &
      dam_merged_normal_velocity(2.0_rk, [4.0_rk, 4.0_rk, 0.0_rk], [0.0_rk, 0.0_rk, 0.0_rk], &
      [1.0_rk, 0.0_rk, 0.0_rk], 0.1_rk), 2.0_rk, 1e-15_rk)

  ! DAM put-back: the slave's normal component becomes the master's, the
  ! tangential one stays.
  block
    real(rk) :: v(3), n(3)
    n = [0.6_rk, 0.8_rk, 0.0_rk]
    v = dam_put_back_velocity([1.0_rk, 2.0_rk, 3.0_rk], n, -0.5_rk)
    call check_close('DAM put-back: normal component = target', dot_product(v, n), -0.5_rk, &
        1e-15_rk)
    call check_close('DAM put-back: tangential component kept', &
        norm2(v - dot_product(v, n) * n), norm2([1.0_rk, 2.0_rk, 3.0_rk] - 2.2_rk * n), &
        1e-15_rk)
  end block

  ! Coulomb friction, DLM facet pair. Masses 2 and 6 (mu = 1.5), normal z,
  ! the hitting side sliding at 0.3 along x (and closing at 0.1), no hydro
  ! force, dt = 0.1. Stick: -mu vt / dt = -4.5 along x, within the limit
  ! 0.5 x 100: after it both sides move at 0.3 - 0.1 x 4.5/2 = 0 + 0.1 x
  ! 4.5/6 = 0.075 along x (sliding stopped, momentum kept).
  block
    real(rk) :: ft(3), n(3)
    n = [0.0_rk, 0.0_rk, 1.0_rk]
    ft = dlm_pair_friction(0.5_rk, 2.0_rk, 6.0_rk, [0.3_rk, 0.0_rk, -0.1_rk], &
        [0.0_rk, 0.0_rk, 0.0_rk], [0.0_rk, 0.0_rk, 0.0_rk], [0.0_rk, 0.0_rk, 0.0_rk], n, &
        0.1_rk, -100.0_rk)
    call check_close('DLM friction, stick: ft_x = -mu vt/dt = -4.5', ft(1), -4.5_rk, 1e-14_rk)
    call check_true('DLM friction, stick: no normal or y component', ft(2) == 0.0_rk .and. &
        ft(3) == 0.0_rk)
    call check_close('DLM friction, stick: both sides at 0.075 after the step', &
        0.3_rk + 0.1_rk * ft(1) / 2.0_rk, 0.0_rk - 0.1_rk * ft(1) / 6.0_rk, 1e-14_rk)
    ! Slip: normal force -3, coefficient 0.5: limited to 1.5, against vt.
    ft = dlm_pair_friction(0.5_rk, 2.0_rk, 6.0_rk, [0.3_rk, 0.0_rk, -0.1_rk], &
        [0.0_rk, 0.0_rk, 0.0_rk], [0.0_rk, 0.0_rk, 0.0_rk], [0.0_rk, 0.0_rk, 0.0_rk], n, &
        0.1_rk, -3.0_rk)
    call check_close('DLM friction, slip: ft_x = -0.5 x 3 = -1.5', ft(1), -1.5_rk, 1e-14_rk)
    ! With hydro forces, sliding along x and y: vh = (0.3, 0.4, 0), its share
    ! of the hydro force (0, -2, 5) (the z part is normal, ignored): free
    ! relative tangential velocity at t + dt (0.3, 0.4 - 0.1 x 2/2) = (0.3,
    ! 0.3); stick -1.5 (0.3, 0.3)/0.1 = (-4.5, -4.5), size 6.36 > limit 1 x
    ! 4: slip, -4 (1, 1)/sqrt(2) = -2.828427 each.
    ft = dlm_pair_friction(1.0_rk, 2.0_rk, 6.0_rk, [0.3_rk, 0.4_rk, 0.0_rk], &
        [0.0_rk, 0.0_rk, 0.0_rk], [0.0_rk, -2.0_rk, 5.0_rk], [0.0_rk, 0.0_rk, 0.0_rk], n, &
        0.1_rk, -4.0_rk)
    call check_close('DLM friction, slip with hydro forces: ft_x = -2 sqrt(2)', ft(1), &
        -2.0_rk * sqrt(2.0_rk), 1e-14_rk)
    call check_close('DLM friction, slip with hydro forces: ft_y = -2 sqrt(2)', ft(2), &
        -2.0_rk * sqrt(2.0_rk), 1e-14_rk)
    call check_close('DLM friction, slip: |ft| = friction |fn| = 4', norm2(ft), 4.0_rk, 1e-14_rk)
    ! Oblique normal (0.6, 0.8, 0): the force has no normal component.
    n = [0.6_rk, 0.8_rk, 0.0_rk]
    ft = dlm_pair_friction(1.0_rk, 2.0_rk, 6.0_rk, [1.0_rk, 2.0_rk, 3.0_rk], &
        [0.0_rk, 0.0_rk, 0.0_rk], [0.0_rk, 0.0_rk, 0.0_rk], [0.0_rk, 0.0_rk, 0.0_rk], n, &
        0.1_rk, -1.0e6_rk)
    call check_close('DLM friction, oblique normal: ft . n = 0', dot_product(ft, n), 0.0_rk, &
        0.0_rk, 1e-12_rk)
    ! vt = (1, 2, 3) - 2.2 n = (-0.32, 0.24, 3): stick -15 vt.
    call check_close('DLM friction, oblique normal: ft_z = -15 x 3 = -45', ft(3), -45.0_rk, &
        1e-14_rk)
    ! No normal force, no friction.
    ft = dlm_pair_friction(1.0_rk, 2.0_rk, 6.0_rk, [1.0_rk, 2.0_rk, 3.0_rk], &
        [0.0_rk, 0.0_rk, 0.0_rk], [0.0_rk, 0.0_rk, 0.0_rk], [0.0_rk, 0.0_rk, 0.0_rk], n, &
        0.1_rk, 0.0_rk)
    call check_true('DLM friction: no normal force, no friction', all(ft == 0.0_rk))

    ! DAM: slave at (0.2, 0, -0.1) after the put-back, master interpolated
    ! (0.05, 0, -0.1), normal z: relative tangential 0.15 along x. Normal
    ! velocity change 0.4, coefficient 0.5: limit 0.2 > 0.15, stick (the
    ! slave takes the master's tangential velocity); with change 0.1 (or
    ! -0.1: the size counts), limit 0.05: slip by 0.05.
    n = [0.0_rk, 0.0_rk, 1.0_rk]
    ft = dam_friction_velocity(0.5_rk, [0.2_rk, 0.0_rk, -0.1_rk], [0.05_rk, 0.0_rk, -0.1_rk], n, &
        0.4_rk)
    call check_close('DAM friction, stick: dv_x = -0.15', ft(1), -0.15_rk, 1e-14_rk)
    call check_true('DAM friction, stick: dv_y = dv_z = 0', ft(2) == 0.0_rk .and. &
        ft(3) == 0.0_rk)
    ft = dam_friction_velocity(0.5_rk, [0.2_rk, 0.0_rk, -0.1_rk], [0.05_rk, 0.0_rk, -0.1_rk], n, &
        -0.1_rk)
    call check_close('DAM friction, slip: dv_x = -0.5 x 0.1 = -0.05', ft(1), -0.05_rk, 1e-14_rk)

    ! The law itself: within the limit unchanged, beyond it scaled to it.
    call check_true('Coulomb limit: stick within the limit', &
        all(coulomb_limit([3.0_rk, -4.0_rk, 0.0_rk], 5.0_rk) == [3.0_rk, -4.0_rk, 0.0_rk]))
    ft = coulomb_limit([3.0_rk, -4.0_rk, 0.0_rk], 1.0_rk)
    call check_close('Coulomb limit: slip, x = 0.6', ft(1), 0.6_rk, 1e-15_rk)
    call check_close('Coulomb limit: slip, y = -0.8', ft(2), -0.8_rk, 1e-15_rk)
    call check_true('Coulomb limit: zero stick, zero limit', &
        all(coulomb_limit([0.0_rk, 0.0_rk, 0.0_rk], 0.0_rk) == 0.0_rk))
  end block

  call check_summary()
end program test_contact_kernels
