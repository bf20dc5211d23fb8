!> Stage drivers of the predictor-corrector cycle: they unpack the types,
!> call the kernels, refresh halos and gather node forces. The cycle itself
!> (which stages, in which order, and where contact goes) is in src/app.
module hydro_driver
  use core_kinds, only: rk
  use core_exact_sum, only: exact_sum_t
  use mesh_local, only: mesh_t
  use material_table, only: material_t, material_eos, material_flow, STRENGTH_NONE, &
      EOS_IDEAL_GAS, EOS_MIE_GRUNEISEN
  use material_strength, only: deviatoric_update, velocity_gradient, equivalent_strain_rate
  use material_failure, only: failure_t, failure_damage_rate, failure_homologous
  use hydro_state, only: state_t, hydro_options_t, HOURGLASS_NONE, HOURGLASS_VISCOUS, &
      HOURGLASS_STIFFNESS, VISCOSITY_EDGE
  use hydro_kernels, only: zone_kinematics, zone_viscosity, zone_corner_forces, zone_work, &
      node_gather_forces, zone_time_step, zone_limited_viscosity, zone_edge_limiter, &
      zone_edge_forces, node_velocity_step, zone_material_sums, zone_heat_flux
  use hydro_boundary, only: boundary_t, boundary_constrain, boundary_pressure_forces, boundary_wall
  implicit none
  private
  public :: hydro_zone_update, hydro_forces, hydro_energy_update, hydro_velocity_update
  public :: hydro_time_step, hydro_energies, material_zones_build, hydro_strength_update
  public :: hydro_material_energies, hydro_heat_flux, hydro_eroded_quiet, first_bad_live

  !> Zones of each material (local indices), for the EOS loops.
  type, public :: material_zones_t
    integer, allocatable :: start(:) !< CSR over materials
    integer, allocatable :: list(:) !< local zones
    integer, allocatable :: zone(:) !< material of each local zone
  end type material_zones_t

contains

  !> Group the local zones by material.
  subroutine material_zones_build(zone_material, nmaterial, mz)
    integer, intent(in) :: zone_material(:)
    integer, intent(in) :: nmaterial
    type(material_zones_t), intent(out) :: mz
    integer :: m, z, k
    allocate(mz%start(nmaterial + 1), mz%list(size(zone_material)))
    mz%zone = zone_material
    k = 0
    mz%start(1) = 1
    do m = 1, nmaterial
      do z = 1, size(zone_material)
        if (zone_material(z) == m) then
          k = k + 1
          mz%list(k) = z
        end if
      end do
      mz%start(m + 1) = k + 1
    end do
  end subroutine material_zones_build

  !> Geometry, density, EOS and viscosity of every local zone at positions x
  !> and velocities v. bad = first local zone with a non-positive volume.
  !> With the edge viscosity the zone q is 0 and state%zone_edge_q holds the
  !> edge limiter and the strong-shock factor (the forces are hydro_forces').
  subroutine hydro_zone_update(mesh, state, materials, mz, opt, bc, x, v, bad)
    type(mesh_t), intent(inout) :: mesh
    type(boundary_t), intent(in) :: bc
    type(state_t), intent(inout) :: state
    type(material_t), intent(in) :: materials(:)
    type(material_zones_t), intent(in) :: mz
    type(hydro_options_t), intent(in) :: opt
    real(rk), intent(in) :: x(:, :), v(:, :)
    integer, intent(out) :: bad
    integer :: z, m
    if (opt%q_limiter) then
      call zone_kinematics(mesh%nzone, mesh%nnode, mesh%zone_node, x, v, state%zone_volume, &
          state%zone_bmatrix, state%zone_length, state%zone_divergence, bad, state%zone_gradient)
    else
      call zone_kinematics(mesh%nzone, mesh%nnode, mesh%zone_node, x, v, state%zone_volume, &
          state%zone_bmatrix, state%zone_length, state%zone_divergence, bad)
    end if
    ! Eroded zones may turn inside out: only a live zone's volume stops the run.
    if (bad > 0 .and. allocated(state%zone_alive)) bad = first_bad_live(state%zone_volume, &
        state%zone_alive)
    do z = 1, mesh%nzone
      ! A tangled zone keeps its last density; the run stops at the end of the cycle.
      if (state%zone_volume(z) > 0.0_rk) state%zone_density(z) = state%zone_mass(z) / &
          state%zone_volume(z)
    end do
    do m = 1, size(materials)
      call material_eos(materials(m), mz%list(mz%start(m):mz%start(m + 1) - 1), &
          state%zone_density, state%zone_energy, state%zone_pressure, state%zone_sound_speed)
    end do
    ! A failed zone carries no tension.
    if (allocated(state%zone_damage)) then
      do z = 1, mesh%nzone
        if (state%zone_damage(z) >= 1.0_rk) state%zone_pressure(z) = &
            max(state%zone_pressure(z), 0.0_rk)
      end do
    end if
    if (opt%viscosity == VISCOSITY_EDGE) then
      if (.not. allocated(state%zone_edge_q)) allocate(state%zone_edge_q(2, mesh%nzone))
      do m = 1, size(materials)
        do z = mz%start(m), mz%start(m + 1) - 1
          state%zone_edge_q(2, mz%list(z)) = shock_factor(materials(m))
        end do
      end do
      ! As for the scalar limiter: owned zones compute it, ghosts receive it.
      call zone_edge_limiter(mesh%nzone_owned, mesh%face_neighbour, mesh%face_neighbour_face, &
          bc%face_symmetric, state%zone_gradient, opt%q_limiter, state%zone_edge_q)
      call mesh%zone_halo%exchange(state%zone_edge_q)
      state%zone_viscosity = 0.0_rk
    else if (opt%q_limiter) then
      ! The limiter needs face neighbours, which outer ghosts lack: owned zones
      ! compute q, ghosts receive it.
      call zone_limited_viscosity(mesh%nzone_owned, mesh%face_neighbour, &
          mesh%face_neighbour_face, bc%face_symmetric, state%zone_gradient, opt%q_linear, &
          opt%q_quadratic, opt%q_linear_limited, state%zone_density, state%zone_sound_speed, &
          state%zone_length, &
          state%zone_divergence, state%zone_viscosity)
      call mesh%zone_halo%exchange(state%zone_viscosity)
    else
      call zone_viscosity(mesh%nzone, opt%q_linear, opt%q_quadratic, state%zone_density, &
          state%zone_sound_speed, state%zone_length, state%zone_divergence, state%zone_viscosity)
    end if
    if (allocated(state%eroded_zones)) call hydro_eroded_quiet(state)
  end subroutine hydro_zone_update

  !> First zone with a non-positive volume among the live ones (0: none).
  pure integer function first_bad_live(volume, alive) result(bad)
    real(rk), intent(in) :: volume(:), alive(:)
    integer :: z
    bad = 0
    do z = 1, size(volume)
      if (.not. (volume(z) > 0.0_rk) .and. alive(z) > 0.0_rk) then
        bad = z
        return
      end if
    end do
  end function first_bad_live

  !> Eroded zones carry nothing and limit no step: pressure, viscosity, sound
  !> speed, divergence (so zone_time_step finds no bound) and deviatoric
  !> stress 0; the edge viscosity's limiter 1 - psi 0.
  subroutine hydro_eroded_quiet(state)
    type(state_t), intent(inout) :: state
    integer :: i, z
    do i = 1, size(state%eroded_zones)
      z = state%eroded_zones(i)
      state%zone_pressure(z) = 0.0_rk
      state%zone_viscosity(z) = 0.0_rk
      state%zone_sound_speed(z) = 0.0_rk
      state%zone_divergence(z) = 0.0_rk
      if (allocated(state%zone_edge_q)) state%zone_edge_q(1, z) = 0.0_rk
      if (allocated(state%zone_stress)) then
        state%zone_stress(:, z) = 0.0_rk
        state%zone_stress_half(:, z) = 0.0_rk
      end if
    end do
  end subroutine hydro_eroded_quiet

  !> Strong-shock factor g of the edge viscosity: (gamma + 1)/4 for an ideal
  !> gas; s/2 for Mie-Gruneisen (Us = c0 + s up: the strong-shock limit of
  !> rho0 Us up is rho0 s up^2, as (gamma + 1)/2 rho0 up^2 for a gas).
  pure real(rk) function shock_factor(mat)
    type(material_t), intent(in) :: mat
    select case (mat%eos)
    case (EOS_IDEAL_GAS)
      shock_factor = 0.25_rk * (mat%gamma + 1.0_rk)
    case (EOS_MIE_GRUNEISEN)
      shock_factor = 0.5_rk * mat%mg%s1
    case default
      shock_factor = 0.5_rk
    end select
  end function shock_factor

  !> Corner forces of every local zone and the force of every owned node
  !> (internal + applied pressure) at positions x, velocities v.
  !> Viscous hourglass control acts once per cycle, in the corrector
  !> (stage_dt > 0), on the step's starting velocities v^n (state's
  !> node_velocity_old) at the mid-step geometry: the half-step lag of a
  !> central-difference code. The predictor's forces are pressure and q only.
  !> Stiffness hourglass control acts in both stages on v (its stress is a
  !> state). docs/theory.md, hourglass control.
  subroutine hydro_forces(mesh, state, opt, bc, x, v, stage_dt, stress)
    type(mesh_t), intent(in) :: mesh
    type(state_t), intent(inout) :: state
    type(hydro_options_t), intent(in) :: opt
    type(boundary_t), intent(inout) :: bc
    real(rk), intent(in) :: x(:, :), v(:, :)
    real(rk), intent(in) :: stage_dt !< 0 in the predictor, dt in the corrector
    real(rk), intent(in), optional :: stress(:, :) !< (6, nzone) deviatoric stress to apply
    integer :: z, k
    real(rk) :: s(6), b(3)
    real(rk) :: unused(3, 4, 1)
    real(rk), allocatable :: kept(:)
    logical :: book
    ! The corrector books the hourglass forces' work.
    book = stage_dt > 0.0_rk .and. allocated(state%zone_hourglass_work)
    ! An eroded zone's forces are dropped below: its hourglass work stays.
    if (book .and. allocated(state%eroded_zones)) kept = &
        state%zone_hourglass_work(state%eroded_zones)
    if (opt%hourglass == HOURGLASS_STIFFNESS) then
      if (book) then
        call zone_corner_forces(mesh%nzone, mesh%nnode, mesh%zone_node, x, v, state%zone_volume, &
            state%zone_bmatrix, state%zone_pressure, state%zone_viscosity, state%zone_density, &
            state%zone_sound_speed, opt%hourglass, opt%hourglass_coefficient, stage_dt, &
            state%zone_hourglass, state%zone_hourglass_new, state%corner_force, &
            state%zone_hourglass_work)
      else
        call zone_corner_forces(mesh%nzone, mesh%nnode, mesh%zone_node, x, v, state%zone_volume, &
            state%zone_bmatrix, state%zone_pressure, state%zone_viscosity, state%zone_density, &
            state%zone_sound_speed, opt%hourglass, opt%hourglass_coefficient, stage_dt, &
            state%zone_hourglass, state%zone_hourglass_new, state%corner_force)
      end if
    else if (opt%hourglass == HOURGLASS_VISCOUS .and. stage_dt > 0.0_rk) then
      if (book) then
        call zone_corner_forces(mesh%nzone, mesh%nnode, mesh%zone_node, x, &
            state%node_velocity_old, state%zone_volume, state%zone_bmatrix, &
            state%zone_pressure, state%zone_viscosity, state%zone_density, &
            state%zone_sound_speed, opt%hourglass, opt%hourglass_coefficient, stage_dt, &
            unused, unused, state%corner_force, state%zone_hourglass_work)
      else
        call zone_corner_forces(mesh%nzone, mesh%nnode, mesh%zone_node, x, &
            state%node_velocity_old, state%zone_volume, state%zone_bmatrix, &
            state%zone_pressure, state%zone_viscosity, state%zone_density, &
            state%zone_sound_speed, opt%hourglass, opt%hourglass_coefficient, stage_dt, &
            unused, unused, state%corner_force)
      end if
    else
      call zone_corner_forces(mesh%nzone, mesh%nnode, mesh%zone_node, x, v, state%zone_volume, &
          state%zone_bmatrix, state%zone_pressure, state%zone_viscosity, state%zone_density, &
          state%zone_sound_speed, HOURGLASS_NONE, opt%hourglass_coefficient, stage_dt, &
          unused, unused, state%corner_force)
    end if
    if (opt%viscosity == VISCOSITY_EDGE) call zone_edge_forces(mesh%nzone, mesh%zone_node, x, v, &
        state%zone_volume, state%zone_density, state%zone_sound_speed, state%zone_edge_q, &
        opt%q_linear, opt%q_quadratic, opt%q_linear_limited, state%corner_force)
    ! Deviatoric part: F_k -= s . dV/dx_k (sigma = -p I + s); zero rows cost little.
    if (present(stress)) then
      do z = 1, mesh%nzone
        s = stress(:, z)
        if (all(s == 0.0_rk)) cycle
        do k = 1, 8
          b = state%zone_bmatrix(:, k, z)
          state%corner_force(1, k, z) = state%corner_force(1, k, z) &
              - (s(1) * b(1) + s(4) * b(2) + s(6) * b(3))
          state%corner_force(2, k, z) = state%corner_force(2, k, z) &
              - (s(4) * b(1) + s(2) * b(2) + s(5) * b(3))
          state%corner_force(3, k, z) = state%corner_force(3, k, z) &
              - (s(6) * b(1) + s(5) * b(2) + s(3) * b(3))
        end do
      end do
    end if
    ! An eroded zone exerts no force.
    if (allocated(state%eroded_zones)) then
      do k = 1, size(state%eroded_zones)
        state%corner_force(:, :, state%eroded_zones(k)) = 0.0_rk
      end do
      if (allocated(kept)) state%zone_hourglass_work(state%eroded_zones) = kept
    end if
    call node_gather_forces(mesh%nnode_owned, 8 * mesh%nzone, mesh%corner_start, &
        mesh%corner_list, state%corner_force, state%node_force)
    call boundary_pressure_forces(bc, mesh, x, state%node_force)
  end subroutine hydro_forces

  !> e = e_old - step * (work of the corner forces on v) / m, every local zone.
  subroutine hydro_energy_update(mesh, state, v, step)
    type(mesh_t), intent(in) :: mesh
    type(state_t), intent(inout) :: state
    real(rk), intent(in) :: v(:, :)
    real(rk), intent(in) :: step
    call zone_work(mesh%nzone, mesh%nnode, mesh%zone_node, state%corner_force, v, &
        state%zone_energy_old, state%zone_mass, step, state%zone_energy)
  end subroutine hydro_energy_update

  !> v_new = v_old + step F / M on owned nodes, constrained; adds the terms of
  !> the boundary work of the step to work (diagnostic; for the final update).
  subroutine hydro_velocity_update(mesh, state, bc, step, v_new, work)
    type(mesh_t), intent(in) :: mesh
    type(state_t), intent(inout) :: state
    type(boundary_t), intent(in) :: bc
    real(rk), intent(in) :: step
    real(rk), intent(inout) :: v_new(:, :)
    type(exact_sum_t), intent(inout), optional :: work !< + its terms, exactly (core_exact_sum)
    integer :: n, k
    real(rk) :: vavg(3)
    call node_velocity_step(mesh%nnode_owned, state%node_velocity_old, state%node_force, &
        state%node_mass, step, v_new)
    call boundary_constrain(bc, v_new, .true.)
    call boundary_wall(bc, state%node_position_old, state%node_velocity_old, v_new, step)
    ! Nodes that left the calculation stay where they are.
    if (allocated(state%dead_nodes)) then
      do k = 1, size(state%dead_nodes)
        v_new(:, state%dead_nodes(k)) = 0.0_rk
      end do
    end if
    ! Work of the constraint and wall reactions and of the applied pressure.
    if (.not. present(work)) return
    do k = 1, bc%nkinematic
      n = bc%kinematic_node(k)
      vavg = 0.5_rk * (state%node_velocity_old(:, n) + v_new(:, n))
      call work%add(dot_product(state%node_mass(n) * (v_new(:, n) - &
          state%node_velocity_old(:, n)) - step * state%node_force(:, n), vavg))
    end do
    do k = 1, bc%npnode
      n = bc%pnode(k)
      vavg = 0.5_rk * (state%node_velocity_old(:, n) + v_new(:, n))
      call work%add(step * dot_product(bc%pnode_force(:, k), vavg))
    end do
  end subroutine hydro_velocity_update

  !> Deviatoric stress of every local zone of a material with strength:
  !> to = return(from + step (2 G D' + W s - s W)) with the velocity gradient of
  !> v on the current B-matrix; plastic strain accumulates when accumulate,
  !> and with it the damage of a material with a failure model (failures).
  !> A failed zone (damage 1) carries no deviatoric stress.
  subroutine hydro_strength_update(mesh, state, materials, mz, v, step, from, to, accumulate, &
      failures)
    type(mesh_t), intent(in) :: mesh
    type(state_t), intent(inout) :: state
    type(material_t), intent(in) :: materials(:)
    type(material_zones_t), intent(in) :: mz
    real(rk), intent(in) :: v(:, :)
    real(rk), intent(in) :: step
    real(rk), intent(in) :: from(:, :)
    real(rk), intent(inout) :: to(:, :)
    logical, intent(in) :: accumulate
    type(failure_t), intent(in), optional :: failures(:) !< per material (damage models)
    integer :: m, i, z, k
    real(rk) :: vz(3, 8), grad(3, 3), dp, shear, yield, hardening, sbar, rate
    logical :: damage, failed
    failed = allocated(state%zone_damage)
    do m = 1, size(materials)
      if (materials(m)%strength == STRENGTH_NONE) cycle
      damage = .false.
      if (present(failures) .and. accumulate) damage = allocated(failures(m)%model)
      do i = mz%start(m), mz%start(m + 1) - 1
        z = mz%list(i)
        if (.not. (state%zone_volume(z) > 0.0_rk)) cycle
        if (failed) then
          if (state%zone_damage(z) >= 1.0_rk) then
            to(:, z) = 0.0_rk
            cycle
          end if
        end if
        do k = 1, 8
          vz(:, k) = v(:, mesh%zone_node(k, z))
        end do
        call velocity_gradient(vz, state%zone_bmatrix(:, :, z), state%zone_volume(z), grad)
        rate = equivalent_strain_rate(grad)
        call material_flow(materials(m), state%zone_pressure(z), state%zone_energy(z), &
            state%zone_density(z), state%zone_plastic_strain(z), rate, &
            shear, yield, hardening)
        call deviatoric_update(from(:, z), grad, step, shear, yield, to(:, z), dp, hardening)
        if (accumulate) state%zone_plastic_strain(z) = state%zone_plastic_strain(z) + dp
        if (accumulate .and. dp > 0.0_rk) then
          ! Plastic work s : d(eps_p) V = sbar dp V (von Mises: the returned
          ! stress is on the yield surface, its equivalent stress sbar).
          sbar = sqrt(1.5_rk * (to(1, z)**2 + to(2, z)**2 + to(3, z)**2 &
              + 2.0_rk * (to(4, z)**2 + to(5, z)**2 + to(6, z)**2)))
          state%zone_plastic_work(z) = state%zone_plastic_work(z) + sbar * dp * &
              state%zone_volume(z)
          ! Damage D += dp / eps_f(sigma*, epsdot*, T*); at 1 the zone has
          ! failed and drops its deviatoric stress now.
          if (damage .and. sbar > 0.0_rk) then
            state%zone_damage(z) = min(1.0_rk, state%zone_damage(z) + dp * &
                failure_damage_rate(failures(m), state%zone_pressure(z), sbar, rate, &
                failure_homologous(materials(m), state%zone_energy(z))))
            if (state%zone_damage(z) >= 1.0_rk) to(:, z) = 0.0_rk
          end if
        end if
      end do
    end do
  end subroutine hydro_strength_update

  !> Artificial heat flux over a step dt (zone_heat_flux), owned zones, from
  !> the zone state of the step's middle (density, sound speed, length,
  !> divergence) and the energies at its end; the caller refreshes the ghosts.
  subroutine hydro_heat_flux(mesh, state, opt, mz, dt)
    type(mesh_t), intent(in) :: mesh
    type(state_t), intent(inout) :: state
    type(hydro_options_t), intent(in) :: opt
    type(material_zones_t), intent(in) :: mz
    real(rk), intent(in) :: dt
    real(rk), allocatable :: e(:)
    e = state%zone_energy
    call zone_heat_flux(mesh%nzone_owned, mesh%face_neighbour, mz%zone, state%zone_mass, &
        state%zone_density, state%zone_sound_speed, state%zone_length, &
        state%zone_divergence, opt%heat_flux_linear, opt%heat_flux_quadratic, dt, e, &
        state%zone_energy)
  end subroutine hydro_heat_flux

  !> Stability limit over owned zones (local), the zone and the reason.
  subroutine hydro_time_step(mesh, state, opt, dt, zone, reason)
    type(mesh_t), intent(in) :: mesh
    type(state_t), intent(in) :: state
    type(hydro_options_t), intent(in) :: opt
    real(rk), intent(out) :: dt
    integer, intent(out) :: zone, reason
    if (opt%viscosity == VISCOSITY_EDGE) then
      call zone_time_step(mesh%nzone_owned, opt%cfl, opt%dvol_max, opt%q_linear, &
          opt%q_quadratic, state%zone_length, state%zone_sound_speed, state%zone_divergence, &
          dt, zone, reason, state%zone_edge_q)
    else
      call zone_time_step(mesh%nzone_owned, opt%cfl, opt%dvol_max, opt%q_linear, &
          opt%q_quadratic, state%zone_length, state%zone_sound_speed, state%zone_divergence, &
          dt, zone, reason)
    end if
  end subroutine hydro_time_step

  !> Local sums over owned zones per material m = zone_material(z):
  !> sums(:, m) = internal energy, kinetic energy (each corner's eighth of the
  !> zone mass at its node's velocity: the nodal masses are the same eighths,
  !> so the sum over materials is the total), plastic work, hourglass work.
  subroutine hydro_material_energies(mesh, state, zone_material, sums)
    type(mesh_t), intent(in) :: mesh
    type(state_t), intent(in) :: state
    integer, intent(in) :: zone_material(:) !< material of each local zone
    real(rk), intent(out) :: sums(:, :) !< (4, nmaterial)
    integer :: z, m
    sums = 0.0_rk
    call zone_material_sums(mesh%nzone_owned, mesh%nnode, mesh%zone_node, zone_material, &
        state%zone_mass, state%zone_energy, state%node_velocity, sums)
    if (allocated(state%zone_plastic_work)) then
      do z = 1, mesh%nzone_owned
        m = zone_material(z)
        sums(3, m) = sums(3, m) + state%zone_plastic_work(z)
      end do
    end if
    if (allocated(state%zone_hourglass_work)) then
      do z = 1, mesh%nzone_owned
        m = zone_material(z)
        sums(4, m) = sums(4, m) + state%zone_hourglass_work(z)
      end do
    end if
  end subroutine hydro_material_energies

  !> Local sums over owned items: internal and kinetic energy, momentum.
  subroutine hydro_energies(mesh, state, sums)
    type(mesh_t), intent(in) :: mesh
    type(state_t), intent(in) :: state
    real(rk), intent(out) :: sums(5) !< internal, kinetic, momentum x, y, z
    sums = 0.0_rk
    call energy_sums(mesh%nzone_owned, mesh%nnode_owned, state%zone_mass, state%zone_energy, &
        state%node_mass, state%node_velocity, sums)
  end subroutine hydro_energies

  !> hydro_energies' sums over zones 1..nz and nodes 1..nn, added to sums.
  subroutine energy_sums(nz, nn, zone_mass, energy, node_mass, v, sums)
    integer, intent(in) :: nz, nn
    real(rk), intent(in) :: zone_mass(nz), energy(nz), node_mass(nn), v(3, nn)
    real(rk), intent(inout) :: sums(5)
    integer :: n, z
    do z = 1, nz
      sums(1) = sums(1) + zone_mass(z) * energy(z)
    end do
    do n = 1, nn
      ! dot_product's order: ((0 + v1 v1) + v2 v2) + v3 v3, 0 + a = a for a >= 0.
      sums(2) = sums(2) + 0.5_rk * node_mass(n) * (v(1, n) * v(1, n) + v(2, n) * v(2, n) &
          + v(3, n) * v(3, n))
      sums(3) = sums(3) + node_mass(n) * v(1, n)
      sums(4) = sums(4) + node_mass(n) * v(2, n)
      sums(5) = sums(5) + node_mass(n) * v(3, n)
    end do
  end subroutine energy_sums

end module hydro_driver
