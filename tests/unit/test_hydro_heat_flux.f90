!> Artificial heat flux kernel (zone_heat_flux) on a row of zones joined
!> face to face: the exchange conserves the internal energy sum m e to
!> round-off; every new energy lies between the old energies of the zone and
!> its neighbours (the cap makes the update a convex combination at any time
!> step); an uncapped face exchanges exactly dt (h_z + h_nb)/2 (L_z + L_nb)/2
!> (e_nb - e_z); a capped one m_z m_nb / (6 (m_z + m_nb)) (e_nb - e_z); zones
!> in expansion, and faces between two materials, exchange nothing.
program test_hydro_heat_flux
  use core_kinds, only: rk
  use hydro_kernels, only: zone_heat_flux
  use check, only: check_close, check_true, check_summary
  implicit none
  real(rk), parameter :: eps = epsilon(1.0_rk)
  integer, parameter :: n = 6
  integer :: neighbour(6, n), material(n), z, trial, seed_size
  integer, allocatable :: seed(:)
  real(rk) :: mass(n), rho(n), c(n), length(n), div(n), e(n), enew(n), r(n)
  real(rk) :: lo, hi, w, h1, h2, a, b, dt
  character(len=64) :: name
  logical :: inside

  ! A row along x: face 6 (xi minus) and face 4 (xi plus); no other neighbours.
  neighbour = 0
  do z = 1, n
    if (z > 1) neighbour(6, z) = z - 1
    if (z < n) neighbour(4, z) = z + 1
  end do
  material = 1

  call random_seed(size=seed_size)
  allocate(seed(seed_size))
  seed = 1987
  call random_seed(put=seed)
  do trial = 1, 20
    call random_number(r)
    mass = 0.5_rk + r
    call random_number(r)
    rho = 0.5_rk + 2.0_rk * r
    call random_number(r)
    c = 0.1_rk + r
    call random_number(r)
    length = 0.05_rk + 0.1_rk * r
    call random_number(r)
    div = -3.0_rk * r
    call random_number(r)
    e = 10.0_rk * r
    ! Coefficients from small (no face capped) to large (every face capped).
    a = 0.1_rk * trial
    b = 0.5_rk * trial**2
    dt = 1.0e-3_rk * trial**2
    call zone_heat_flux(n, neighbour, material, mass, rho, c, length, div, a, b, dt, e, enew)
    write(name, '(a,i0)') 'energy sum conserved to round-off, case ', trial
    call check_close(trim(name), sum(mass * enew), sum(mass * e), 16 * eps)
    inside = .true.
    do z = 1, n
      lo = minval(e(max(1, z - 1):min(n, z + 1)))
      hi = maxval(e(max(1, z - 1):min(n, z + 1)))
      if (enew(z) < lo - 4 * eps * hi .or. enew(z) > hi + 4 * eps * hi) inside = .false.
    end do
    write(name, '(a,i0)') 'no new extremum (convex update), case ', trial
    call check_true(trim(name), inside)
  end do

  ! Two zones (the row's first pair alone): uncapped and capped conductance.
  mass = 1.0_rk
  mass(2) = 3.0_rk
  rho = 1.0_rk
  c = 1.0_rk
  length = 0.1_rk
  length(2) = 0.2_rk
  div = -1.0_rk
  div(2) = -2.0_rk
  e = 0.0_rk
  e(1) = 1.0_rk
  e(2) = 5.0_rk
  material(3:) = 2 ! zone 3 onwards: another material, cut off from the pair
  a = 0.5_rk
  b = 1.0_rk
  dt = 1.0e-3_rk
  call zone_heat_flux(n, neighbour, material, mass, rho, c, length, div, a, b, dt, e, enew)
  h1 = rho(1) * length(1) * (a * c(1) - b * length(1) * div(1))
  h2 = rho(2) * length(2) * (a * c(2) - b * length(2) * div(2))
  w = dt * 0.5_rk * (h1 + h2) * 0.5_rk * (length(1) + length(2))
  call check_true('the pair is below the cap', w < mass(1) * mass(2) / (6.0_rk * (mass(1) + &
      mass(2))))
  call check_close('uncapped: zone 1 gains w (e2 - e1) / m1', enew(1), e(1) + w * (e(2) - e(1)) &
      / mass(1), 4 * eps)
  call check_close('uncapped: zone 2 loses as much', enew(2), e(2) - w * (e(2) - e(1)) &
      / mass(2), 4 * eps)
  call check_true('no exchange across the material boundary', enew(3) == e(3))
  dt = 1.0e3_rk
  call zone_heat_flux(n, neighbour, material, mass, rho, c, length, div, a, b, dt, e, enew)
  w = mass(1) * mass(2) / (6.0_rk * (mass(1) + mass(2)))
  call check_close('capped: zone 1 gains m1 m2 / (6 (m1 + m2)) (e2 - e1) / m1', enew(1), &
      e(1) + w * (e(2) - e(1)) / mass(1), 4 * eps)
  call check_close('capped: zone 2 loses as much', enew(2), e(2) - w * (e(2) - e(1)) &
      / mass(2), 4 * eps)

  ! Expansion everywhere: nothing moves, at any coefficient.
  material = 1
  div = 1.0_rk
  call zone_heat_flux(n, neighbour, material, mass, rho, c, length, div, a, b, dt, e, enew)
  call check_true('expansion: no exchange', all(enew == e))
  ! One zone in compression: its faces carry half its conductance.
  div(2) = -1.0_rk
  dt = 1.0e-3_rk
  call zone_heat_flux(n, neighbour, material, mass, rho, c, length, div, a, b, dt, e, enew)
  h2 = rho(2) * length(2) * (a * c(2) - b * length(2) * div(2))
  w = dt * 0.5_rk * h2 * 0.5_rk * (length(1) + length(2))
  call check_close('one side compressed: half its conductance', enew(1), &
      e(1) + w * (e(2) - e(1)) / mass(1), 4 * eps)
  call check_true('two zones away from it: no exchange', all(enew(4:) == e(4:)))

  call check_summary()

end program test_hydro_heat_flux
