!> Mie-Grueneisen EOS (Steinberg form) with the Cu and Al 6061-T6 data of
!> docs/problems.md ("Material data"): (a) Hugoniot pressure and Hugoniot states, (b) sound speed
!> against a central difference of p along the isentrope de = p/rho^2 drho,
!> (c) energy inversion, (d) ambient state, (e) pressure cut-off and
!> sound-speed floor.
!>
!> On (a): with p_H = rho0 c0^2 mu (1 + mu)/D^2 and E_H = p_H mu/(2 (1 + mu)),
!> p_H + (gamma0 + b mu)(E - E_H) is algebraically the implemented compression
!> formula for every b, so p(rho_H, e_H) = p_H holds to round-off both with
!> b = 0 and with Steinberg's b /= 0; both cases are checked.
program test_eos_mie_gruneisen
  use core_kinds, only: rk
  use eos_mie_gruneisen, only: mie_gruneisen_t, mg_pressure, mg_sound_speed, &
      mg_energy_from_pressure, mg_hugoniot_pressure, MG_SOUND_SPEED_FLOOR
  use check, only: check_close, check_true, check_summary
  implicit none
  real(rk), parameter :: eps = epsilon(1.0_rk)
  type(mie_gruneisen_t), parameter :: copper = mie_gruneisen_t(rho0=8.93_rk, c0=0.394_rk, &
      s1=1.489_rk, gamma0=2.02_rk, b=0.47_rk)
  type(mie_gruneisen_t), parameter :: aluminium = mie_gruneisen_t(rho0=2.703_rk, &
      c0=0.524_rk, s1=1.40_rk, gamma0=1.97_rk, b=0.48_rk)
  real(rk), parameter :: particle_velocities(3) = [0.01_rk, 0.05_rk, 0.1_rk]
  real(rk), parameter :: density_ratios(7) = &
      [0.8_rk, 0.9_rk, 0.97_rk, 1.02_rk, 1.1_rk, 1.3_rk, 1.6_rk]
  real(rk), parameter :: energies(3) = [0.0_rk, 0.001_rk, 0.01_rk]
  type(mie_gruneisen_t) :: m, m_b0
  real(rk) :: up, us, rho_h, mu_h, p_h, e_h, rho, e, p, h, c, fd, pp, pm
  real(rk) :: rarray(3), parray(3)
  integer :: imat, i, j
  character(len=80) :: name
  character(len=2) :: tag

  do imat = 1, 2
    if (imat == 1) then
      m = copper
      tag = 'Cu'
    else
      m = aluminium
      tag = 'Al'
    end if
    m_b0 = m
    m_b0%b = 0.0_rk

    ! (a) Hugoniot states from the jump conditions.
    do i = 1, size(particle_velocities)
      up = particle_velocities(i)
      us = m%c0 + m%s1 * up
      rho_h = m%rho0 * us / (us - up)
      mu_h = up / (us - up)
      p_h = m%rho0 * us * up
      e_h = 0.5_rk * up**2
      write(name, '(a,a,f5.2)') tag, ' (a) p_H(mu_H) = rho0 Us up, up =', up
      call check_close(trim(name), mg_hugoniot_pressure(m, mu_h), p_h, 1.0e-12_rk)
      write(name, '(a,a,f5.2)') tag, ' (a) p(rho_H, e_H) = p_H with b = 0, up =', up
      call check_close(trim(name), mg_pressure(m_b0, rho_h, e_h), p_h, 1.0e-12_rk)
      write(name, '(a,a,f5.2)') tag, ' (a) p(rho_H, e_H) = p_H with b /= 0, up =', up
      call check_close(trim(name), mg_pressure(m, rho_h, e_h), p_h, 1.0e-12_rk)
      write(name, '(a,a,f5.2)') tag, ' (a) rel. diff. p(rho_H, e_H)/p_H - 1, b /= 0, up =', up
      call check_close(trim(name), mg_pressure(m, rho_h, e_h) / p_h - 1.0_rk, 0.0_rk, &
          0.0_rk, atol=1.0e-12_rk)
      write(name, '(a,a,f5.2)') tag, ' (c) e(rho_H, p_H) = up^2/2, up =', up
      call check_close(trim(name), mg_energy_from_pressure(m, rho_h, p_h), e_h, 1.0e-12_rk)
    end do

    ! (b) c^2 = dp/drho along the isentrope, central difference, step 1e-4 rho.
    ! The first-order energy step e +- (p/rho^2) h misses the isentrope by the
    ! same O(h^2) on both sides, which cancels in the central difference.
    do i = 1, size(density_ratios)
      do j = 1, size(energies)
        rho = density_ratios(i) * m%rho0
        e = energies(j)
        p = mg_pressure(m, rho, e)
        c = mg_sound_speed(m, rho, e, p)
        h = 1.0e-4_rk * rho
        pp = mg_pressure(m, rho + h, e + p / rho**2 * h)
        pm = mg_pressure(m, rho - h, e - p / rho**2 * h)
        fd = (pp - pm) / (2.0_rk * h)
        write(name, '(a,a,f4.2,a,f5.3)') tag, ' (b) c^2 vs isentrope FD, rho/rho0 =', &
            density_ratios(i), ', e =', e
        call check_close(trim(name), c**2, fd, 1.0e-6_rk)
      end do
    end do

    ! (c) Energy inversion.
    do i = 1, size(density_ratios)
      do j = 1, size(energies)
        rho = density_ratios(i) * m%rho0
        e = energies(j)
        write(name, '(a,a,f4.2,a,f5.3)') tag, ' (c) e(rho, p(rho, e)) = e, rho/rho0 =', &
            density_ratios(i), ', e =', e
        call check_close(trim(name), mg_energy_from_pressure(m, rho, mg_pressure(m, rho, e)), &
            e, 1000 * eps, atol=1000 * eps * m%c0**2)
      end do
    end do

    ! (d) Ambient state.
    call check_close(tag//' (d) p(rho0, 0) = 0', mg_pressure(m, m%rho0, 0.0_rk), 0.0_rk, &
        0.0_rk, atol=1.0e-14_rk)
    call check_close(tag//' (d) c(rho0, 0) = c0', &
        mg_sound_speed(m, m%rho0, 0.0_rk, mg_pressure(m, m%rho0, 0.0_rk)), m%c0, 1.0e-14_rk)
    ! Across mu = 0 the two branches agree in p and in c.
    rho = m%rho0 * (1.0_rk + 1.0e-9_rk)
    c = mg_sound_speed(m, rho, 0.001_rk, mg_pressure(m, rho, 0.001_rk))
    rho = m%rho0 * (1.0_rk - 1.0e-9_rk)
    call check_close(tag//' (d) c continuous across mu = 0', &
        mg_sound_speed(m, rho, 0.001_rk, mg_pressure(m, rho, 0.001_rk)), c, 1.0e-8_rk)
  end do

  ! (e) Cut-off: a strongly expanded cold copper zone (p = -0.14 Mbar uncut).
  m = copper
  m%p_min = -0.01_rk
  rho = 0.9_rk * m%rho0
  p = mg_pressure(m, rho, 0.0_rk)
  call check_close('Cu (e) cut-off: p(0.9 rho0, 0) = p_min', p, -0.01_rk, 0.0_rk)
  call check_true('Cu (e) uncut pressure is below p_min', &
      mg_pressure(copper, rho, 0.0_rk) < -0.1_rk)
  ! Sound speed of the cut zone: uncut derivatives with the cut p.
  c = mg_sound_speed(m, rho, 0.0_rk, p)
  call check_close('Cu (e) cut zone c^2 = c0^2 + p rho0 (gamma0 + b mu)/rho^2', c**2, &
      m%c0**2 + p * m%rho0 * (m%gamma0 - 0.1_rk * m%b) / rho**2, 100 * eps)
  call check_close('Cu (e) cut-off leaves a compressed state alone', &
      mg_pressure(m, 1.2_rk * m%rho0, 0.001_rk), &
      mg_pressure(copper, 1.2_rk * m%rho0, 0.001_rk), 0.0_rk)
  ! Floor: at rho0/2, cold and uncut, c^2 from the formula is negative.
  rho = 0.5_rk * copper%rho0
  c = mg_sound_speed(copper, rho, 0.0_rk, mg_pressure(copper, rho, 0.0_rk))
  call check_close('Cu (e) sound-speed floor in strong tension', c, &
      MG_SOUND_SPEED_FLOOR * copper%c0, 4 * eps)

  ! Elemental use: scalar material, array states.
  rarray = [0.9_rk, 1.0_rk, 1.2_rk] * copper%rho0
  parray = mg_pressure(copper, rarray, 0.001_rk)
  call check_close('elemental: array call matches scalar call', parray(3), &
      mg_pressure(copper, rarray(3), 0.001_rk), 0.0_rk)

  call check_summary()
end program test_eos_mie_gruneisen
