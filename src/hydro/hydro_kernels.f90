!> Zone and node kernels of the compatible staggered scheme (plain arrays,
!> no MPI, no I/O). The drivers in hydro_driver call them stage by stage.
module hydro_kernels
  use core_kinds, only: rk
  use mesh_geometry, only: hex_geometry_lanes, HEX_LANES, HOURGLASS_BASE, &
      SIGN_XI, SIGN_ETA, SIGN_ZETA
  use hydro_state, only: HOURGLASS_VISCOUS, HOURGLASS_STIFFNESS
  use, intrinsic :: iso_c_binding, only: c_double
  implicit none
  private

  interface
    !> The C library's cube root (within 1 ulp in glibc, and cheaper than
    !> x**(1/3) through pow).
    pure function c_cbrt(x) bind(c, name='cbrt') result(y)
      import :: c_double
      real(c_double), value, intent(in) :: x
      real(c_double) :: y
    end function c_cbrt
  end interface
  public :: zone_kinematics, zone_viscosity, zone_corner_forces, zone_work
  public :: node_gather_forces, zone_time_step, node_velocity_step
  public :: zone_material_sums, zone_heat_flux
  public :: zone_limited_viscosity, zone_edge_limiter, zone_edge_forces

  integer, parameter, public :: DT_CFL = 1, DT_VOLUME = 2
  real(rk), parameter :: SYMMETRY_RATIO = 1.0_rk !< a mirror neighbour has the same rate
  !> Faces (mesh_geometry order) on the minus and plus side of each logical direction.
  integer, parameter :: FACE_MINUS(3) = [6, 3, 1], FACE_PLUS(3) = [4, 5, 2]
  !> Logical direction normal to each face.
  integer, parameter :: FACE_DIRECTION(6) = [3, 3, 2, 1, 2, 1]
  !> The 12 edges of the hex (VTK order; node k has the logical signs of
  !> SIGN_XI, SIGN_ETA, SIGN_ZETA): their two nodes (4 edges along xi, then eta,
  !> then zeta) and the two faces that share them, faces numbered 1 xi-, 2 xi+, 3 eta-, 4 eta+,
  !> 5 zeta-, 6 zeta+ (EDGE_FACE_NODE).
  integer, parameter :: EDGE_NODE(2, 12) = reshape([1, 2, 4, 3, 5, 6, 8, 7, &
      1, 4, 2, 3, 5, 8, 6, 7, 1, 5, 2, 6, 3, 7, 4, 8], [2, 12])
  integer, parameter :: EDGE_FACE(2, 12) = reshape([3, 5, 4, 5, 3, 6, 4, 6, &
      1, 5, 2, 5, 1, 6, 2, 6, 1, 3, 2, 3, 2, 4, 1, 4], [2, 12])
  integer, parameter :: EDGE_FACE_NODE(4, 6) = reshape([1, 4, 5, 8, 2, 3, 6, 7, &
      1, 2, 5, 6, 3, 4, 7, 8, 1, 2, 3, 4, 5, 6, 7, 8], [4, 6])

contains

  !> Volume, B-matrix, characteristic length and velocity divergence of zones
  !> 1..n, and (when gradient is present) the stretching rate along each logical
  !> direction, g_d = dv_d . dx_d / |dx_d|^2 (dx_d, dv_d: differences between
  !> opposite face centres). bad returns the first zone with a non-positive or
  !> NaN volume (0 = none).
  subroutine zone_kinematics(n, nnode, zone_node, x, v, volume, b, length, divergence, bad, &
      gradient)
    integer, intent(in) :: n
    integer, intent(in) :: nnode !< nodes the zones refer to (x, v)
    integer, intent(in) :: zone_node(8, n)
    real(rk), intent(in) :: x(3, nnode), v(3, nnode)
    real(rk), intent(inout) :: volume(n), b(3, 8, n), length(n), divergence(n)
    integer, intent(out) :: bad
    real(rk), intent(inout), optional :: gradient(3, n)
    ! Zones in blocks of HEX_LANES, the zone of the block first in every work
    ! array (hex_geometry_lanes); each zone gets the operations of one zone at
    ! a time in the same order (bitwise the same results).
    real(rk), dimension(HEX_LANES, 3, 8) :: xb, vb, bl
    real(rk) :: vol(HEX_LANES), len(HEX_LANES), ax(HEX_LANES, 3, 3), dvdt(HEX_LANES)
    real(rk) :: div(HEX_LANES), dv(HEX_LANES, 3, 3), l2(HEX_LANES), num(HEX_LANES)
    real(rk) :: g(HEX_LANES, 3)
    integer :: zl(HEX_LANES), z0, nb, i, z, k, d
    logical :: with_gradient
    with_gradient = present(gradient)
    bad = 0
    do z0 = 1, n, HEX_LANES
      nb = min(HEX_LANES, n - z0 + 1)
      ! Lanes past the last zone repeat it; they are not stored.
      do i = 1, HEX_LANES
        zl(i) = z0 + min(i, nb) - 1
      end do
      call gather_lanes(zl, zone_node, x, v, xb, vb)
      ! ax(:, :, d): the signed sums of the positions along each logical
      ! direction (SIGN_XI, SIGN_ETA, SIGN_ZETA), from the same pass as the volume.
      call hex_geometry_lanes(xb, vol, bl, len, ax)
      dvdt = 0.0_rk
      do k = 1, 8
        dvdt = dvdt + bl(:, 1, k) * vb(:, 1, k) + bl(:, 2, k) * vb(:, 2, k) &
            + bl(:, 3, k) * vb(:, 3, k)
      end do
      ! (Divisions by 1 in the lanes of tangled zones, whose values are not used.)
      div = dvdt / merge(vol, 1.0_rk, vol > 0.0_rk)
      if (with_gradient) then
        ! Signed sums with the signs of SIGN_XI, SIGN_ETA, SIGN_ZETA written out (the
        ! same additions in the same order as a loop over k from zero: bitwise equal).
        do d = 1, 3
          dv(:, d, 1) = -vb(:, d, 1) + vb(:, d, 2) + vb(:, d, 3) - vb(:, d, 4) - vb(:, d, 5) &
              + vb(:, d, 6) + vb(:, d, 7) - vb(:, d, 8)
          dv(:, d, 2) = -vb(:, d, 1) - vb(:, d, 2) + vb(:, d, 3) + vb(:, d, 4) - vb(:, d, 5) &
              - vb(:, d, 6) + vb(:, d, 7) + vb(:, d, 8)
          dv(:, d, 3) = -vb(:, d, 1) - vb(:, d, 2) - vb(:, d, 3) - vb(:, d, 4) + vb(:, d, 5) &
              + vb(:, d, 6) + vb(:, d, 7) + vb(:, d, 8)
        end do
        do d = 1, 3
          l2 = ax(:, 1, d)**2 + ax(:, 2, d)**2 + ax(:, 3, d)**2
          num = dv(:, 1, d) * ax(:, 1, d) + dv(:, 2, d) * ax(:, 2, d) + dv(:, 3, d) * ax(:, 3, d)
          g(:, d) = merge(num / merge(l2, 1.0_rk, l2 > 0.0_rk), 0.0_rk, l2 > 0.0_rk)
        end do
      end if
      do i = 1, nb
        z = z0 + i - 1
        b(:, :, z) = bl(i, :, :)
        volume(z) = vol(i)
        if (.not. (vol(i) > 0.0_rk)) then
          if (bad == 0) bad = z
          length(z) = 0.0_rk
          divergence(z) = 0.0_rk
          if (with_gradient) gradient(:, z) = 0.0_rk
          cycle
        end if
        length(z) = len(i)
        divergence(z) = div(i)
        if (with_gradient) gradient(:, z) = g(i, :)
      end do
    end do
  end subroutine zone_kinematics

  !> Quadratic + linear artificial viscosity, active in compression only:
  !> q = rho (C2 L^2 D^2 + C1 c L |D|) for D = div v < 0.
  subroutine zone_viscosity(n, q_linear, q_quadratic, density, sound_speed, length, &
      divergence, q)
    integer, intent(in) :: n
    real(rk), intent(in) :: q_linear, q_quadratic
    real(rk), intent(in) :: density(:), sound_speed(:), length(:), divergence(:)
    real(rk), intent(inout) :: q(:)
    integer :: z
    real(rk) :: du
    do z = 1, n
      if (divergence(z) < 0.0_rk) then
        du = length(z) * divergence(z)
        q(z) = density(z) * (q_quadratic * du * du - q_linear * sound_speed(z) * du)
      else
        q(z) = 0.0_rk
      end if
    end do
  end subroutine zone_viscosity

  !> Corner forces F(:, k, z) = (p + q) dV/dx_k + Flanagan-Belytschko hourglass
  !> forces, f_k = -sum_m gamma_km Q_m with Q_m = kappa/4 rho c V^2/3 (gamma_m . v)
  !> (viscous) or its time integral with rate kappa/4 rho c^2 V^1/3 (stiffness). With stiffness hourglass control the generalised hourglass stress
  !> used is hg + stage_dt/2 * rate, and hg_new = hg + stage_dt * rate.
  !> With hg_work present, each zone's hg_work grows by the energy its
  !> hourglass forces take from the velocities v over stage_dt:
  !> -stage_dt sum_k f_k . v_k = stage_dt sum_m Q_m . (gamma_m . v).
  subroutine zone_corner_forces(n, nnode, zone_node, x, v, volume, b, pressure, q, density, &
      sound_speed, hourglass, coefficient, stage_dt, hg, hg_new, force, hg_work)
    integer, intent(in) :: n
    integer, intent(in) :: nnode !< nodes the zones refer to (x, v)
    integer, intent(in) :: zone_node(8, n)
    real(rk), intent(in) :: x(3, nnode), v(3, nnode), volume(n), b(3, 8, n)
    real(rk), intent(in) :: pressure(n), q(n), density(n), sound_speed(n)
    integer, intent(in) :: hourglass !< HOURGLASS_* type
    real(rk), intent(in) :: coefficient !< hourglass coefficient
    real(rk), intent(in) :: stage_dt !< 0 in the predictor, dt in the corrector
    real(rk), intent(in) :: hg(:, :, :) !< stiffness state at t^n (unused otherwise)
    real(rk), intent(inout) :: hg_new(:, :, :) !< stiffness state at t^n+1
    real(rk), intent(inout) :: force(3, 8, n)
    real(rk), intent(inout), optional :: hg_work(n)
    ! Zones go in blocks of LANES, the zone index of the block first in every
    ! work array, so that each statement is a vector operation over the block's
    ! zones; every zone gets the same operations in the same order as one zone
    ! at a time would (bitwise the same forces).
    integer, parameter :: LANES = HEX_LANES
    real(rk) :: xb(LANES, 3, 8), vb(LANES, 3, 8), bb(LANES, 3, 8), hx(LANES, 3, 4)
    real(rk) :: gam(LANES, 8, 4), rate(LANES, 3, 4), stress(LANES, 3, 4)
    real(rk) :: ptot(LANES), rvol(LANES), scale(LANES), r(LANES), f(LANES), fp(LANES)
    real(rk) :: w(LANES), vol
    logical :: live(LANES)
    integer :: zl(LANES), z0, nb, i, z, k, m, d
    logical :: with_hourglass, book
    with_hourglass = hourglass == HOURGLASS_VISCOUS .or. hourglass == HOURGLASS_STIFFNESS
    book = present(hg_work)
    if (.not. with_hourglass) then
      do z = 1, n
        ptot(1) = pressure(z) + q(z)
        do k = 1, 8
          force(:, k, z) = ptot(1) * b(:, k, z)
        end do
      end do
      return
    end if
    do z0 = 1, n, LANES
      nb = min(LANES, n - z0 + 1)
      ! Lanes past the last zone repeat it; they are not stored.
      do i = 1, LANES
        zl(i) = z0 + min(i, nb) - 1
      end do
      call gather_lanes(zl, zone_node, x, v, xb, vb)
      do k = 1, 8
        do i = 1, LANES
          bb(i, 1, k) = b(1, k, zl(i))
          bb(i, 2, k) = b(2, k, zl(i))
          bb(i, 3, k) = b(3, k, zl(i))
        end do
      end do
      ! A tangled zone (the run stops at the end of the cycle) gets no
      ! hourglass force; its lane computes with volume 1 and is not used.
      do i = 1, LANES
        z = zl(i)
        ptot(i) = pressure(z) + q(z)
        live(i) = volume(z) > 0.0_rk
        vol = 1.0_rk
        if (live(i)) vol = volume(z)
        rvol(i) = 1.0_rk / vol
        if (hourglass == HOURGLASS_VISCOUS) then
          scale(i) = 0.25_rk * coefficient * density(z) * sound_speed(z) * c_cbrt(vol)**2
        else
          scale(i) = 0.25_rk * coefficient * density(z) * sound_speed(z)**2 * c_cbrt(vol)
        end if
      end do
      do d = 1, 3
        hx(:, d, 1) = xb(:, d, 1) - xb(:, d, 2) + xb(:, d, 3) - xb(:, d, 4) + xb(:, d, 5) &
            - xb(:, d, 6) + xb(:, d, 7) - xb(:, d, 8)
        hx(:, d, 2) = xb(:, d, 1) + xb(:, d, 2) - xb(:, d, 3) - xb(:, d, 4) - xb(:, d, 5) &
            - xb(:, d, 6) + xb(:, d, 7) + xb(:, d, 8)
        hx(:, d, 3) = xb(:, d, 1) - xb(:, d, 2) - xb(:, d, 3) + xb(:, d, 4) - xb(:, d, 5) &
            + xb(:, d, 6) + xb(:, d, 7) - xb(:, d, 8)
        hx(:, d, 4) = -xb(:, d, 1) + xb(:, d, 2) - xb(:, d, 3) + xb(:, d, 4) + xb(:, d, 5) &
            - xb(:, d, 6) + xb(:, d, 7) - xb(:, d, 8)
      end do
      do k = 1, 8
        do m = 1, 4
          gam(:, k, m) = HOURGLASS_BASE(k, m) - rvol * (hx(:, 1, m) * bb(:, 1, k) &
              + hx(:, 2, m) * bb(:, 2, k) + hx(:, 3, m) * bb(:, 3, k))
        end do
      end do
      do m = 1, 4
        do d = 1, 3
          r = 0.0_rk
          do k = 1, 8
            r = r + gam(:, k, m) * vb(:, d, k)
          end do
          rate(:, d, m) = r
        end do
      end do
      if (hourglass == HOURGLASS_VISCOUS) then
        do m = 1, 4
          do d = 1, 3
            stress(:, d, m) = scale * rate(:, d, m)
          end do
        end do
      else
        do i = 1, LANES
          z = zl(i)
          stress(i, :, :) = hg(:, :, z) + 0.5_rk * stage_dt * scale(i) * rate(i, :, :)
          if (i <= nb .and. live(i)) hg_new(:, :, z) = hg(:, :, z) + stage_dt * scale(i) * &
              rate(i, :, :)
        end do
      end if
      if (book) then
        w = 0.0_rk
        do m = 1, 4
          do d = 1, 3
            w = w + stress(:, d, m) * rate(:, d, m)
          end do
        end do
        do i = 1, nb
          if (live(i)) hg_work(z0 + i - 1) = hg_work(z0 + i - 1) + stage_dt * w(i)
        end do
      end if
      if (.not. all(live)) then
        do i = 1, LANES
          if (live(i)) cycle
          gam(i, :, :) = 0.0_rk
          stress(i, :, :) = 0.0_rk
        end do
      end if
      do k = 1, 8
        do d = 1, 3
          fp = ptot * bb(:, d, k)
          f = fp - gam(:, k, 1) * stress(:, d, 1)
          f = f - gam(:, k, 2) * stress(:, d, 2)
          f = f - gam(:, k, 3) * stress(:, d, 3)
          f = f - gam(:, k, 4) * stress(:, d, 4)
          if (nb == LANES) then
            force(d, k, z0:z0 + LANES - 1) = f
          else
            force(d, k, z0:z0 + nb - 1) = f(1:nb)
          end if
        end do
      end do
    end do
  end subroutine zone_corner_forces

  !> Energy update of zones 1..n by the work of their corner forces on the
  !> node velocities v: e = e_old - step * w / m, w = sum_k F(:, k, z) . v(:, node k).
  subroutine zone_work(n, nnode, zone_node, force, v, e_old, mass, step, e)
    integer, intent(in) :: n
    integer, intent(in) :: nnode !< nodes the zones refer to (v)
    integer, intent(in) :: zone_node(8, n)
    real(rk), intent(in) :: force(3, 8, n), v(3, nnode), e_old(n), mass(n)
    real(rk), intent(in) :: step
    real(rk), intent(inout) :: e(n)
    integer :: z, k, node
    real(rk) :: w
    do z = 1, n
      w = 0.0_rk
      do k = 1, 8
        node = zone_node(k, z)
        w = w + force(1, k, z) * v(1, node) + force(2, k, z) * v(2, node) &
            + force(3, k, z) * v(3, node)
      end do
      e(z) = e_old(z) - step * w / mass(z)
    end do
  end subroutine zone_work

  !> Node force = sum of its corner forces, in the fixed order of the corner lists.
  subroutine node_gather_forces(n, ncorner, corner_start, corner_list, corner_force, force)
    integer, intent(in) :: n
    integer, intent(in) :: ncorner !< 8 nzone
    integer, intent(in) :: corner_start(n + 1), corner_list(corner_start(n + 1) - 1)
    real(rk), intent(in) :: corner_force(3, ncorner) !< the (3, 8, nzone) array, flat
    real(rk), intent(inout) :: force(3, n)
    integer :: i, j, c
    real(rk) :: f1, f2, f3
    do i = 1, n
      f1 = 0.0_rk
      f2 = 0.0_rk
      f3 = 0.0_rk
      do j = corner_start(i), corner_start(i + 1) - 1
        c = corner_list(j)
        f1 = f1 + corner_force(1, c)
        f2 = f2 + corner_force(2, c)
        f3 = f3 + corner_force(3, c)
      end do
      force(1, i) = f1
      force(2, i) = f2
      force(3, i) = f3
    end do
  end subroutine node_gather_forces

  !> v_new = v_old + step F / M of nodes 1..n.
  subroutine node_velocity_step(n, v_old, force, mass, step, v_new)
    integer, intent(in) :: n
    real(rk), intent(in) :: v_old(3, n), force(3, n), mass(n)
    real(rk), intent(in) :: step
    real(rk), intent(inout) :: v_new(3, n)
    integer :: i
    do i = 1, n
      v_new(1, i) = v_old(1, i) + step * force(1, i) / mass(i)
      v_new(2, i) = v_old(2, i) + step * force(2, i) / mass(i)
      v_new(3, i) = v_old(3, i) + step * force(3, i) / mass(i)
    end do
  end subroutine node_velocity_step

  !> Per-material sums over zones 1..n, m = zone_material(z): sums(1, m) +=
  !> mass e, sums(2, m) += each corner's eighth of the zone mass at its node's
  !> velocity, m/16 sum_k |v_k|^2 (the halves of the kinetic energies).
  subroutine zone_material_sums(n, nnode, zone_node, zone_material, mass, energy, v, sums)
    integer, intent(in) :: n
    integer, intent(in) :: nnode !< nodes the zones refer to (v)
    integer, intent(in) :: zone_node(8, n), zone_material(n)
    real(rk), intent(in) :: mass(n), energy(n), v(3, nnode)
    real(rk), intent(inout) :: sums(:, :) !< (>= 2, nmaterial)
    integer :: z, k, m, node
    real(rk) :: v2
    real(rk), allocatable :: speed2(:)
    ! |v|^2 once per node (one gather of a scalar per corner, not of a vector);
    ! dot_product's order: ((0 + v1 v1) + v2 v2) + v3 v3, 0 + a = a for a >= 0.
    allocate(speed2(nnode))
    do node = 1, nnode
      speed2(node) = v(1, node) * v(1, node) + v(2, node) * v(2, node) + v(3, node) * v(3, node)
    end do
    do z = 1, n
      m = zone_material(z)
      sums(1, m) = sums(1, m) + mass(z) * energy(z)
      v2 = 0.0_rk
      do k = 1, 8
        v2 = v2 + speed2(zone_node(k, z))
      end do
      sums(2, m) = sums(2, m) + 0.0625_rk * mass(z) * v2
    end do
  end subroutine zone_material_sums

  !> Smallest stable step over zones 1..n: CFL with the viscous signal speed
  !> b = C1 c + C2 f L |D| in compression, dt = cfl L / (b + sqrt(b^2 + c^2)),
  !> and the relative volume change limit dt = dvol_max / |D|. f = 1, or
  !> quadratic_factor(2, z) * 2 with the edge viscosity (its strong-shock
  !> quadratic coefficient is C2 (gamma + 1)/2 in one dimension).
  subroutine zone_time_step(n, cfl, dvol_max, q_linear, q_quadratic, length, sound_speed, &
      divergence, dt, zone, reason, quadratic_factor)
    integer, intent(in) :: n
    real(rk), intent(in) :: cfl, dvol_max, q_linear, q_quadratic
    real(rk), intent(in) :: length(n), sound_speed(n), divergence(n)
    real(rk), intent(out) :: dt !< smallest step (huge if n = 0)
    integer, intent(out) :: zone !< the zone that sets it
    integer, intent(out) :: reason !< DT_CFL or DT_VOLUME
    real(rk), intent(in), optional :: quadratic_factor(:, :) !< (2, nzone) zone_edge_q
    integer :: z
    real(rk) :: bq, c, trial, c2
    logical :: edge, volume_bound
    edge = present(quadratic_factor)
    c2 = q_quadratic
    dt = huge(1.0_rk)
    zone = 0
    reason = DT_CFL
    do z = 1, n
      c = sound_speed(z)
      bq = 0.0_rk
      if (edge) c2 = 2.0_rk * q_quadratic * quadratic_factor(2, z)
      if (divergence(z) < 0.0_rk) bq = q_linear * c - c2 * length(z) * divergence(z)
      if (bq + c > 0.0_rk) then
        trial = cfl * length(z) / (bq + sqrt(bq * bq + c * c))
        if (trial < dt) then
          dt = trial
          zone = z
          reason = DT_CFL
        end if
      end if
      ! |D| dt > dvol_max; while dt is still huge (no CFL bound yet: cold,
      ! unstrained zones so far) the product would overflow, so compare |D|
      ! with dvol_max / huge instead.
      if (dt < huge(1.0_rk)) then
        volume_bound = abs(divergence(z)) * dt > dvol_max
      else
        volume_bound = abs(divergence(z)) > dvol_max / huge(1.0_rk)
      end if
      if (volume_bound) then
        dt = dvol_max / abs(divergence(z))
        zone = z
        reason = DT_VOLUME
      end if
    end do
  end subroutine zone_time_step

  !> Artificial heat flux (W. F. Noh, J. Comput. Phys. 72 (1987) 78-120),
  !> zones 1..n, over a step dt, energies e (specific, before the flux) into
  !> energy. Across each face to a neighbour of the same material the zones
  !> exchange w (e_nb - e_z) of internal energy, with the conductance
  !>   w = min(dt (h_z + h_nb)/2 (L_z + L_nb)/2, m_z m_nb / (6 (m_z + m_nb))),
  !>   h = rho L (a c + b L |D|) in compression (D = div v < 0), 0 otherwise,
  !> (the flux H = h grad e through a face of area ~ L^2 over a distance ~ L).
  !> The cap is the conductance that would equalize the two zones' energies
  !> in one step shared among a zone's 6 faces: with it the new energy is a
  !> convex combination of the old ones (no new extremum, no sign change)
  !> at any time step. w is symmetric in z and nb and e_nb - e_z antisymmetric,
  !> bit for bit: the pair's exchanges cancel exactly, and a face across a
  !> rank boundary gives both ranks the same value.
  subroutine zone_heat_flux(n, neighbour, material, mass, density, sound_speed, length, &
      divergence, a, b, dt, e, energy)
    integer, intent(in) :: n
    integer, intent(in) :: neighbour(:, :) !< (6, nzone) face neighbours
    integer, intent(in) :: material(:)
    real(rk), intent(in) :: mass(:), density(:), sound_speed(:), length(:), divergence(:)
    real(rk), intent(in) :: a, b, dt
    real(rk), intent(in) :: e(:)
    real(rk), intent(inout) :: energy(:)
    integer :: z, f, nb
    real(rk), allocatable :: h(:)
    real(rk) :: w, de
    ! Conductivities of every zone the owned ones see (ghosts included), once.
    allocate(h(size(e)))
    do z = 1, size(e)
      h(z) = 0.0_rk
      if (divergence(z) < 0.0_rk) h(z) = density(z) * length(z) * (a * sound_speed(z) &
          - b * length(z) * divergence(z))
    end do
    do z = 1, n
      de = 0.0_rk
      do f = 1, 6
        nb = neighbour(f, z)
        if (nb <= 0) cycle
        if (material(nb) /= material(z)) cycle
        w = dt * (0.5_rk * (h(z) + h(nb))) * (0.5_rk * (length(z) + length(nb)))
        w = min(w, mass(z) * mass(nb) / (6.0_rk * (mass(z) + mass(nb))))
        de = de + w * (e(nb) - e(z))
      end do
      energy(z) = e(z) + de / mass(z)
    end do

  end subroutine zone_heat_flux

  !> Monotonic (Christensen-type) limited viscosity of zones 1..n. Along each
  !> logical direction d in compression (g_d < 0) the limiter is
  !> phi_d = max(0, min((r- + r+)/2, 2 r-, 2 r+, 1)), r+- the neighbours'
  !> stretching rates over the zone's own; the zone takes the compression-weighted
  !> mean phi = sum_d |g_d| phi_d / sum_d |g_d| over those directions (a weakly
  !> compressed direction with a noisy ratio, as near the axis of a converging
  !> flow, no longer switches on the whole zone's q; a plane shock along a mesh
  !> direction is unchanged) and
  !> q = rho (1 - phi)^2 C2 (L D)^2 + rho (1 - phi_l) C1 c L |D| for D = div v < 0,
  !> phi_l = phi when linear_limited (default), else 0: an unlimited linear term
  !> dissipates smooth and weak waves (an elastic bar loses 3.6% of its rebound)
  !> and preheats a cold converging inflow (Noh).
  !> A missing neighbour counts as r = 1 on a symmetry plane, r = 0 elsewhere.
  subroutine zone_limited_viscosity(n, neighbour, neighbour_face, symmetric, gradient, &
      q_linear, q_quadratic, linear_limited, density, sound_speed, length, divergence, q)
    integer, intent(in) :: n
    integer, intent(in) :: neighbour(:, :), neighbour_face(:, :) !< (6, nzone)
    logical, intent(in) :: symmetric(:, :) !< (6, nzone) face on a symmetry plane
    real(rk), intent(in) :: gradient(:, :)
    real(rk), intent(in) :: q_linear, q_quadratic
    logical, intent(in) :: linear_limited !< limit the linear term too
    real(rk), intent(in) :: density(:), sound_speed(:), length(:), divergence(:)
    real(rk), intent(inout) :: q(:)
    integer :: z
    real(rk) :: phi, du, phi_linear
    do z = 1, n
      if (divergence(z) >= 0.0_rk) then
        q(z) = 0.0_rk
        cycle
      end if
      phi = zone_limiter(z, neighbour, neighbour_face, symmetric, gradient)
      du = length(z) * divergence(z)
      phi_linear = 0.0_rk
      if (linear_limited) phi_linear = phi
      q(z) = density(z) * (q_quadratic * (du * (1.0_rk - phi))**2 &
          - q_linear * sound_speed(z) * du * (1.0_rk - phi_linear))
    end do
  end subroutine zone_limited_viscosity

  !> The limiter phi of zone z (zone_limited_viscosity's notes): the
  !> compression-weighted mean over the logical directions d in compression
  !> (g_d < 0) of phi_d = max(0, min((r- + r+)/2, 2 r-, 2 r+, 1)), r+- the
  !> face neighbours' stretching rates along d over the zone's own (a missing
  !> neighbour: r = 1 on a symmetry plane, 0 elsewhere); 1 (no viscosity)
  !> where the zone is compressed along no direction.
  pure real(rk) function zone_limiter(z, neighbour, neighbour_face, symmetric, gradient) &
      result(phi)
    integer, intent(in) :: z
    integer, intent(in) :: neighbour(:, :), neighbour_face(:, :) !< (6, nzone)
    logical, intent(in) :: symmetric(:, :) !< (6, nzone) face on a symmetry plane
    real(rk), intent(in) :: gradient(:, :) !< (3, nzone) stretching rates
    integer :: d
    real(rk) :: g, rm, rp, wsum
    phi = 0.0_rk
    wsum = 0.0_rk
    do d = 1, 3
      g = gradient(d, z)
      if (g >= 0.0_rk) cycle
      rm = ratio(FACE_MINUS(d))
      rp = ratio(FACE_PLUS(d))
      phi = phi - g * max(0.0_rk, min(0.5_rk * (rm + rp), 2.0_rk * rm, 2.0_rk * rp, 1.0_rk))
      wsum = wsum - g
    end do
    if (wsum > 0.0_rk) then
      phi = phi / wsum
    else
      phi = 1.0_rk
    end if

  contains

    pure real(rk) function ratio(face)
      integer, intent(in) :: face
      integer :: nb
      nb = neighbour(face, z)
      if (nb > 0) then
        ratio = gradient(FACE_DIRECTION(neighbour_face(face, z)), nb) / g
      else if (symmetric(face, z)) then
        ratio = SYMMETRY_RATIO
      else
        ratio = 0.0_rk
      end if
    end function ratio

  end function zone_limiter

  !> Limiter of the edge viscosity, zones 1..n: edge_q(1, z) = 1 - phi with
  !> phi the zone's limiter of zone_limited_viscosity (the compression-weighted
  !> mean of the directional Christensen limiters over the directions the zone
  !> is compressed along; phi = 1, no edge viscosity, when it is compressed
  !> along none). With limited false, edge_q(1, z) = 1. edge_q(2, :) is left alone.
  !> (A limiter per edge direction, 1 - phi_d, was tried: it lets the zones
  !> along the symmetry axes of Noh's implosion collapse sideways, 30^3 tangles
  !> at t = 0.5995.)
  subroutine zone_edge_limiter(n, neighbour, neighbour_face, symmetric, gradient, limited, &
      edge_q)
    integer, intent(in) :: n
    integer, intent(in) :: neighbour(:, :), neighbour_face(:, :) !< (6, nzone)
    logical, intent(in) :: symmetric(:, :) !< (6, nzone) face on a symmetry plane
    real(rk), intent(in) :: gradient(:, :) !< (3, nzone) stretching rates
    logical, intent(in) :: limited
    real(rk), intent(inout) :: edge_q(:, :) !< (2, nzone)
    integer :: z
    do z = 1, n
      if (limited) then
        edge_q(1, z) = 1.0_rk - zone_limiter(z, neighbour, neighbour_face, symmetric, gradient)
      else
        edge_q(1, z) = 1.0_rk
      end if
    end do
  end subroutine zone_edge_limiter

  !> Edge-centred artificial viscosity (E. J. Caramana, M. J. Shashkov and
  !> P. P. Whalen, J. Comput. Phys. 144 (1998) 70-97), added to the corner
  !> forces of zones 1..n. For each of a zone's 12 edges a -> b with
  !> dx = x_b - x_a, du = v_b - v_a in compression (du . dx < 0):
  !>   mu = rho (1 - psi) [C2 g |du| + sqrt(C2^2 g^2 |du|^2 + C1^2 c^2)],
  !>   g = (gamma + 1)/4 (edge_q(2, z)), 1 - psi = edge_q(1, z) (zone_edge_limiter);
  !> the edge's viscous stress mu |du| acts along du/|du| through A, the part
  !> along the edge of the area vector of the zone's median-mesh surface that
  !> separates a from b (the quadrilateral edge midpoint, face centre, zone
  !> centre, face centre): F_a += mu A du, F_b -= mu A du. The pair is equal and
  !> opposite (no momentum), and its work on the node velocities,
  !> -mu A |du|^2 <= 0, goes into the zone's internal energy through the
  !> compatible update. A tangled zone gets none.
  subroutine zone_edge_forces(n, zone_node, x, v, volume, density, sound_speed, edge_q, &
      q_linear, q_quadratic, linear_limited, force)
    integer, intent(in) :: n
    integer, intent(in) :: zone_node(:, :)
    real(rk), intent(in) :: x(:, :), v(:, :), volume(:), density(:), sound_speed(:)
    real(rk), intent(in) :: edge_q(:, :) !< (2, nzone) 1 - psi and (gamma + 1)/4
    real(rk), intent(in) :: q_linear, q_quadratic
    logical, intent(in) :: linear_limited !< (1 - psi) on the linear term too
    real(rk), intent(inout) :: force(:, :, :)
    real(rk) :: xz(3, 8), vz(3, 8), centre(3), face(3, 6), dx(3), du(3), mid(3), r(3), s(3)
    real(rk) :: area(3), du2, dx2, dux, k2, lin2, mu, f(3), wq, wl
    integer :: z, k, e, ia, ib, node
    do z = 1, n
      if (.not. (volume(z) > 0.0_rk)) cycle
      wq = edge_q(1, z)
      wl = wq
      if (.not. linear_limited) wl = 1.0_rk
      if (.not. (wl > 0.0_rk)) cycle
      do k = 1, 8
        node = zone_node(k, z)
        xz(:, k) = x(:, node)
        vz(:, k) = v(:, node)
      end do
      centre = 0.125_rk * (xz(:, 1) + xz(:, 2) + xz(:, 3) + xz(:, 4) + xz(:, 5) + xz(:, 6) &
          + xz(:, 7) + xz(:, 8))
      do k = 1, 6
        face(:, k) = 0.25_rk * (xz(:, EDGE_FACE_NODE(1, k)) + xz(:, EDGE_FACE_NODE(2, k)) &
            + xz(:, EDGE_FACE_NODE(3, k)) + xz(:, EDGE_FACE_NODE(4, k)))
      end do
      k2 = q_quadratic * edge_q(2, z)
      lin2 = (q_linear * sound_speed(z))**2
      do e = 1, 12
        ia = EDGE_NODE(1, e)
        ib = EDGE_NODE(2, e)
        dx = xz(:, ib) - xz(:, ia)
        du = vz(:, ib) - vz(:, ia)
        dux = du(1) * dx(1) + du(2) * dx(2) + du(3) * dx(3)
        if (.not. (dux < 0.0_rk)) cycle
        dx2 = dx(1)**2 + dx(2)**2 + dx(3)**2
        ! Median-mesh surface of the edge: area vector 1/2 (centre - mid) x
        ! (face2 - face1) of the quadrilateral (its diagonals' cross product).
        mid = 0.5_rk * (xz(:, ia) + xz(:, ib))
        r = centre - mid
        s = face(:, EDGE_FACE(2, e)) - face(:, EDGE_FACE(1, e))
        area(1) = r(2) * s(3) - r(3) * s(2)
        area(2) = r(3) * s(1) - r(1) * s(3)
        area(3) = r(1) * s(2) - r(2) * s(1)
        du2 = du(1)**2 + du(2)**2 + du(3)**2
        mu = density(z) * (wq * k2 * sqrt(du2) + sqrt(wq * wq * k2 * k2 * du2 + wl * wl * lin2)) &
            * 0.5_rk * &
            abs(area(1) * dx(1) + area(2) * dx(2) + area(3) * dx(3)) / sqrt(dx2)
        f = mu * du
        force(:, ia, z) = force(:, ia, z) + f
        force(:, ib, z) = force(:, ib, z) - f
      end do
    end do
  end subroutine zone_edge_forces

  !> The positions and velocities of the corners of HEX_LANES zones zl, the
  !> zone index first (the work arrays of the 4-zone kernels).
  pure subroutine gather_lanes(zl, zone_node, x, v, xb, vb)
    integer, intent(in) :: zl(HEX_LANES)
    integer, intent(in) :: zone_node(:, :)
    real(rk), intent(in) :: x(:, :), v(:, :)
    real(rk), intent(out) :: xb(HEX_LANES, 3, 8), vb(HEX_LANES, 3, 8)
    integer :: i, k, node
    do k = 1, 8
      do i = 1, HEX_LANES
        node = zone_node(k, zl(i))
        xb(i, 1, k) = x(1, node)
        xb(i, 2, k) = x(2, node)
        xb(i, 3, k) = x(3, node)
        vb(i, 1, k) = v(1, node)
        vb(i, 2, k) = v(2, node)
        vb(i, 3, k) = v(3, node)
      end do
    end do
  end subroutine gather_lanes

end module hydro_kernels
