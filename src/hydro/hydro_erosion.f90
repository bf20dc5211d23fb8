!> Failure and erosion at the end of a cycle (docs/design.md, "Failure and
!> erosion"): spall failure, then the erosion decision of each owned live
!> zone from its own state (a failed zone of an eroding material; the
!> distortion criteria of &erosion), the liveness of the ghosts through the
!> zone halo, the lists of eroded zones and of the nodes no live zone uses
!> (their kinetic energy booked, their velocity 0), and the material zone
!> lists without the eroded zones (so EOS and strength skip them). Nothing
!> is allocated and nothing runs for a deck without failure or erosion.
module hydro_erosion
  use core_kinds, only: rk
  use mesh_local, only: mesh_t
  use material_failure, only: failure_t, erosion_spec_t
  use hydro_state, only: state_t, hydro_options_t, VISCOSITY_EDGE
  use hydro_kernels, only: zone_time_step, zone_kinematics
  use hydro_driver, only: material_zones_t, hydro_eroded_quiet, first_bad_live
  use parallel_env, only: par_sum
  implicit none
  private
  public :: erosion_on, erosion_allocate, erosion_restore, erosion_step

contains

  !> Some zone may be eroded: a material erodes its failed zones, or the deck
  !> has an &erosion group.
  pure logical function erosion_on(failures, spec)
    type(failure_t), intent(in) :: failures(:)
    type(erosion_spec_t), intent(in) :: spec
    erosion_on = any(failures%erode) .or. spec%given
  end function erosion_on

  !> The failure and erosion fields of a fresh state: damage 0 (a material
  !> that can fail), every zone live, nothing booked (erosion on).
  subroutine erosion_allocate(mesh, state, failures, spec)
    type(mesh_t), intent(in) :: mesh
    type(state_t), intent(inout) :: state
    type(failure_t), intent(in) :: failures(:)
    type(erosion_spec_t), intent(in) :: spec
    if (any(failures%fails())) then
      allocate(state%zone_damage(mesh%nzone))
      state%zone_damage = 0.0_rk
    end if
    if (.not. erosion_on(failures, spec)) return
    allocate(state%zone_alive(mesh%nzone), state%node_eroded_kinetic(mesh%nnode))
    state%zone_alive = 1.0_rk
    state%node_eroded_kinetic = 0.0_rk
    allocate(state%eroded_zones(0), state%dead_nodes(0))
  end subroutine erosion_allocate

  !> After the initial state or a restart read (node_position_initial set):
  !> the ghosts' liveness, the initial volumes (&erosion volume_ratio), the
  !> lists and the material zone lists. Collective.
  subroutine erosion_restore(mesh, state, mz, spec)
    type(mesh_t), intent(inout) :: mesh
    type(state_t), intent(inout) :: state
    type(material_zones_t), intent(inout) :: mz
    type(erosion_spec_t), intent(in) :: spec
    real(rk), allocatable :: b(:, :, :), length(:), divergence(:), v(:, :)
    integer :: bad
    if (.not. allocated(state%zone_alive)) return
    call mesh%zone_halo%exchange(state%zone_alive)
    if (spec%volume_ratio > 0.0_rk) then
      allocate(state%zone_volume_initial(mesh%nzone), b(3, 8, mesh%nzone))
      allocate(length(mesh%nzone), divergence(mesh%nzone), v(3, mesh%nnode))
      v = 0.0_rk
      call zone_kinematics(mesh%nzone, mesh%nnode, mesh%zone_node, &
          state%node_position_initial, v, state%zone_volume_initial, b, length, divergence, bad)
    end if
    call rebuild_lists(mesh, state, mz, .false.)
  end subroutine erosion_restore

  !> End of a cycle: spall failure of the live zones, the erosion decision of
  !> the owned live zones, and on an erosion anywhere (nnew > 0, the same on
  !> every rank) the ghosts' liveness, the lists, the booking of the nodes
  !> that leave and the eroded zones quieted. bad_half and bad (the step's
  !> first zones with a non-positive volume) are taken back when that zone
  !> is now eroded. Collective when erosion is on.
  subroutine erosion_step(mesh, state, mz, failures, spec, opt, bad_half, bad, nnew)
    type(mesh_t), intent(inout) :: mesh
    type(state_t), intent(inout) :: state
    type(material_zones_t), intent(inout) :: mz
    type(failure_t), intent(in) :: failures(:)
    type(erosion_spec_t), intent(in) :: spec
    type(hydro_options_t), intent(in) :: opt
    integer, intent(inout) :: bad_half, bad
    integer, intent(out) :: nnew !< zones eroded this cycle over all ranks
    integer :: m, i, z, nlocal, iz, reason
    real(rk) :: dtz
    logical :: erode
    nnew = 0
    if (.not. allocated(state%zone_damage) .and. .not. allocated(state%zone_alive)) return
    ! Spall: a live zone whose pressure fell below -spall_strength fails.
    if (allocated(state%zone_damage)) then
      do m = 1, size(failures)
        if (.not. (failures(m)%spall_strength > 0.0_rk)) cycle
        do i = mz%start(m), mz%start(m + 1) - 1
          z = mz%list(i)
          if (.not. (state%zone_pressure(z) < -failures(m)%spall_strength)) cycle
          ! Failed from now: no tension, no deviatoric stress.
          state%zone_damage(z) = 1.0_rk
          state%zone_pressure(z) = 0.0_rk
          if (allocated(state%zone_stress)) state%zone_stress(:, z) = 0.0_rk
        end do
      end do
    end if
    if (.not. allocated(state%zone_alive)) return
    nlocal = 0
    do z = 1, mesh%nzone_owned
      if (state%zone_alive(z) == 0.0_rk) cycle
      m = mz%zone(z)
      erode = .false.
      if (failures(m)%erode .and. allocated(state%zone_damage)) erode = &
          state%zone_damage(z) >= 1.0_rk
      if (.not. erode .and. spec%given) then
        if (spec%block(mesh%zone_block(z))) then
          ! A zone turned inside out is always eroded; then the thresholds.
          erode = .not. (state%zone_volume(z) > 0.0_rk)
          if (.not. erode .and. spec%volume_ratio > 0.0_rk) erode = &
              state%zone_volume(z) < spec%volume_ratio * state%zone_volume_initial(z)
          if (.not. erode .and. spec%dt_fraction > 0.0_rk) then
            if (opt%viscosity == VISCOSITY_EDGE) then
              call zone_time_step(1, opt%cfl, opt%dvol_max, opt%q_linear, opt%q_quadratic, &
                  state%zone_length(z:z), state%zone_sound_speed(z:z), &
                  state%zone_divergence(z:z), dtz, iz, reason, state%zone_edge_q(:, z:z))
            else
              call zone_time_step(1, opt%cfl, opt%dvol_max, opt%q_linear, opt%q_quadratic, &
                  state%zone_length(z:z), state%zone_sound_speed(z:z), &
                  state%zone_divergence(z:z), dtz, iz, reason)
            end if
            erode = dtz < spec%dt_fraction * state%dt_reference
          end if
        end if
      end if
      if (erode) then
        state%zone_alive(z) = 0.0_rk
        nlocal = nlocal + 1
      end if
    end do
    nnew = par_sum(nlocal)
    if (nnew == 0) return
    call mesh%zone_halo%exchange(state%zone_alive)
    call rebuild_lists(mesh, state, mz, .true.)
    ! The nodes that left now have velocity 0 on their owners: the ghosts too.
    call mesh%node_halo%exchange(state%node_velocity)
    if (bad > 0) then
      if (state%zone_alive(bad) == 0.0_rk) bad = first_bad_live(state%zone_volume, &
          state%zone_alive)
    end if
    if (bad_half > 0) then
      if (state%zone_alive(bad_half) == 0.0_rk) bad_half = 0
    end if
  end subroutine erosion_step

  !> The lists of eroded zones (local) and of owned nodes no live zone uses
  !> from zone_alive; a node that leaves now books its kinetic energy and
  !> stops; the material zone lists without the eroded zones; eroded zones'
  !> pressure, viscosity, sound speed, divergence and stress 0.
  subroutine rebuild_lists(mesh, state, mz, book)
    type(mesh_t), intent(in) :: mesh
    type(state_t), intent(inout) :: state
    type(material_zones_t), intent(inout) :: mz
    !> book the kinetic energy of the nodes found to have left (false after a
    !> restart read: their energy is the dump's and their velocity 0)
    logical, intent(in) :: book
    integer :: z, n, j, k, m, nz
    logical :: live
    logical, allocatable :: dead_before(:)
    real(rk), allocatable :: v(:)
    state%eroded_zones = pack([(z, z = 1, mesh%nzone)], state%zone_alive == 0.0_rk)
    allocate(dead_before(mesh%nnode_owned))
    dead_before = .false.
    dead_before(state%dead_nodes) = .true.
    do n = 1, mesh%nnode_owned
      if (dead_before(n)) cycle
      live = .false.
      do j = mesh%corner_start(n), mesh%corner_start(n + 1) - 1
        if (state%zone_alive((mesh%corner_list(j) - 1) / 8 + 1) > 0.0_rk) then
          live = .true.
          exit
        end if
      end do
      if (live) cycle
      dead_before(n) = .true.
      if (.not. book) cycle
      v = state%node_velocity(:, n)
      state%node_eroded_kinetic(n) = 0.5_rk * state%node_mass(n) * (v(1) * v(1) + &
          v(2) * v(2) + v(3) * v(3))
      state%node_velocity(:, n) = 0.0_rk
    end do
    state%dead_nodes = pack([(n, n = 1, mesh%nnode_owned)], dead_before)
    ! Material zone lists: live zones only, in the same order.
    k = 0
    nz = size(mz%zone)
    mz%start(1) = 1
    do m = 1, size(mz%start) - 1
      do z = 1, nz
        if (mz%zone(z) == m .and. state%zone_alive(z) > 0.0_rk) then
          k = k + 1
          mz%list(k) = z
        end if
      end do
      mz%start(m + 1) = k + 1
    end do
    call hydro_eroded_quiet(state)
  end subroutine rebuild_lists

end module hydro_erosion
