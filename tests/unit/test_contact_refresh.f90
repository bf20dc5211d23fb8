!> contact_surface_refresh: surfaces given by blocks follow the live zones
!> during a run. On the deck tests/unit/data/refresh_blocks.nml (block a,
!> 4^3 zones, symmetry on xmin and ymin, under block b):
!> * a refresh with every zone live rebuilds exactly the set-up's contact
!>   (contact nodes, surfaces with their face ids, owners, masses, owned
!>   nodes, sagittas, reach, size);
!> * with block a's top layer of zones masked, surface a is the exterior of
!>   the 4 x 4 x 3 zones left: 56 faces (12 + 12 on xmax and ymax, 16 + 16
!>   on zmin and the new top), its highest node at z = 0.75, every contact
!>   node owned by exactly one rank;
!> * the offsets follow the surfaces (contact_depths before the refresh,
!>   contact_refresh_offsets after): with block b's bottom face lowered to
!>   z = 0.7, into block a's masked top layer, every node of a's new top
!>   face (z = 0.75) takes its depth in b as its offset, the distance to
!>   b's nearest face: min(0.05, 1 - x, 1 - y) (x = 0 and y = 0 are
!>   symmetry planes, no faces); b's bottom nodes, 0.3 deep before and
!>   0.05 now, keep none (a penetration that got smaller is the contact's
!>   to remove); a mutation that gave every node its depth now, or none,
!>   fails one of the two;
!> * the next stages run a new global search on the new surfaces and the
!>   contact forces stay finite;
!> * the owner directory (contact_parts) holds each contact node exactly
!>   once, on the rank mod(global id, ranks), with its mesh owner: the
!>   entries number the contact nodes, and the entries naming rank r
!>   number r's owned contact nodes, each of which its directory rank
!>   holds (a directory that dropped, doubled or misfiled a node, or named
!>   a wrong owner, fails one of these).
!> On 1 and 3 ranks. Usage: test_contact_refresh DECK.
program test_contact_refresh
  use, intrinsic :: iso_fortran_env, only: output_unit
  use core_kinds, only: rk, i8
  use core_status, only: status_t
  use core_timer, only: timers_t, wall_time
  use parallel_env, only: par_init, par_finalize, par_sum, par_max, par_rank, par_size, &
      par_sum_array
  use io_h5, only: h5_library_open
  use io_deck, only: config_t, deck_read
  use mesh_local, only: mesh_t
  use hydro_state, only: state_t
  use hydro_boundary, only: boundary_t, BC_SYMMETRY, BC_WALL
  use hydro_driver, only: material_zones_t
  use io_probe, only: probes_t
  use contact_enforce, only: contact_t, contact_apply, contact_surface_refresh, side_context_t
  use contact_monitor, only: contact_depths, contact_refresh_offsets
  use app_setup, only: setup_run
  use check, only: check_true, check_summary
  implicit none
  character(len=512) :: deck
  character(len=400) :: msg
  type(config_t) :: config
  type(status_t) :: status
  type(mesh_t) :: mesh
  type(boundary_t) :: bc
  type(state_t) :: state
  type(material_zones_t) :: mz
  type(contact_t) :: ct, before
  type(probes_t) :: probes
  type(timers_t) :: timers
  type(side_context_t) :: context
  real(rk), allocatable :: flag(:), force(:, :), xm(:, :), depth(:, :)
  integer(i8), allocatable :: gid(:)
  logical, allocatable :: in_b(:)
  real(rk) :: expected, worst_a, worst_b
  integer :: n
  logical, allocatable :: live(:)
  real(rk), allocatable :: named(:), held(:)
  real(rk) :: ztop, zc
  integer :: ierr, z, i, stage, searches
  logical :: same, finite

  call par_init()
  call get_command_argument(1, deck)
  call h5_library_open(ierr, msg)
  call deck_read(trim(deck), config, status)
  call timers%add('restart read')
  call setup_run(config, '', .false., mesh, bc, state, mz, ct, probes, timers, status)
  call check_true('set-up', status%ok())
  context%block_names = config%blocks(:)%name
  context%closed_sets = pack(config%boundaries(:)%set, config%boundaries(:)%kind == &
      BC_SYMMETRY .or. config%boundaries(:)%kind == BC_WALL)

  ! Every zone live: the set-up again.
  before = ct
  allocate(live(mesh%nzone))
  live = .true.
  call contact_surface_refresh(ct, mesh, state%node_position, state%node_mass, live, context)
  same = ct%nall == before%nall
  if (same) same = all(ct%all_gid == before%all_gid) .and. ct%nown == before%nown
  if (same) same = all(ct%own_contact == before%own_contact) .and. &
      all(ct%own_local == before%own_local) .and. all(ct%own_mass == before%own_mass) .and. &
      all(ct%own_rigid .eqv. before%own_rigid) .and. all(ct%dir_gid == before%dir_gid) .and. &
      all(ct%dir_owner == before%dir_owner)
  do i = 1, ct%npair
    if (.not. same) exit
    associate(p => ct%pairs(i), q => before%pairs(i))
      same = p%all_a%nseg == q%all_a%nseg .and. p%all_b%nseg == q%all_b%nseg
      if (same) same = all(p%all_a%segments == q%all_a%segments) .and. &
          all(p%all_b%segments == q%all_b%segments) .and. &
          all(p%all_a%segment_id == q%all_a%segment_id) .and. &
          all(p%sag_a == q%sag_a) .and. all(p%sag_b == q%sag_b) .and. &
          p%reach == q%reach .and. p%size == q%size .and. all(p%offset == q%offset)
    end associate
  end do
  call check_true('a refresh with every zone live rebuilds the set-up exactly', &
      par_sum(merge(0, 1, same)) == 0)

  ! Block a's top layer masked (owned zones; the ghosts' through the halo).
  allocate(flag(mesh%nzone))
  flag = 0.0_rk
  do z = 1, mesh%nzone_owned
    zc = sum(state%node_position(3, mesh%zone_node(:, z))) / 8.0_rk
    flag(z) = merge(0.0_rk, 1.0_rk, mesh%zone_block(z) == 1 .and. zc > 0.75_rk)
  end do
  call mesh%zone_halo%halo_exchange_scalar(flag)
  live = flag > 0.5_rk
  ! Block b's bottom face lowered to z = 0.7 (positions for the offsets).
  allocate(in_b(mesh%nnode))
  in_b = .false.
  do z = 1, mesh%nzone
    if (mesh%zone_block(z) == 2) in_b(mesh%zone_node(:, z)) = .true.
  end do
  xm = state%node_position
  where (in_b .and. abs(xm(3, :) - 1.0_rk) < 1.0e-12_rk) xm(3, :) = 0.7_rk
  call contact_depths(ct, xm, gid, depth)
  call contact_surface_refresh(ct, mesh, state%node_position, state%node_mass, live, context)
  call contact_refresh_offsets(ct, xm, gid, depth)
  worst_a = -1.0_rk
  worst_b = -1.0_rk
  do i = 1, ct%nown
    n = ct%own_local(i)
    if (.not. in_b(n) .and. abs(xm(3, n) - 0.75_rk) < 1.0e-12_rk) then
      expected = min(0.05_rk, 1.0_rk - xm(1, n), 1.0_rk - xm(2, n))
      worst_a = max(worst_a, abs(ct%pairs(1)%offset(i) - expected))
    else if (in_b(n) .and. abs(xm(3, n) - 0.7_rk) < 1.0e-12_rk) then
      worst_b = max(worst_b, abs(ct%pairs(1)%offset(i)))
    end if
  end do
  worst_a = par_max(worst_a)
  worst_b = par_max(worst_b)
  if (par_rank() == 0) write(output_unit, '(a,es10.3,a,es10.3)') &
      'offsets: a''s new top, largest error ', worst_a, '; b''s bottom, largest ', worst_b
  ! (depths of a plane box geometry: exact but for the rounding of 0.75 - 0.7)
  call check_true('a node that joined takes its depth as offset (to 1e-12)', &
      worst_a >= 0.0_rk .and. worst_a < 1.0e-12_rk)
  call check_true('a node less deep than before keeps no offset', &
      worst_b >= 0.0_rk .and. worst_b < 1.0e-12_rk)
  call check_true('surface a: 56 faces of the 4 x 4 x 3 zones left', ct%pairs(1)%all_a%nseg == 56)
  call check_true('surface b unchanged (125 zones: 25 + 25 + 25 + 25 faces)', &
      ct%pairs(1)%all_b%nseg == before%pairs(1)%all_b%nseg)
  ztop = -huge(1.0_rk)
  do i = 1, ct%nown
    if (ct%pairs(1)%own_in_a(i)) ztop = max(ztop, state%node_position(3, ct%own_local(i)))
  end do
  ztop = par_max(ztop)
  call check_true('surface a ends at the masked layer (z = 0.75)', abs(ztop - 0.75_rk) < 1.0e-12_rk)
  call check_true('every contact node owned by exactly one rank', par_sum(ct%nown) == ct%nall)

  ! The next stages search the new surfaces.
  searches = ct%rebuilds
  allocate(force(3, size(state%node_position, 2)))
  finite = .true.
  do stage = 1, 4
    force = 0.0_rk
    call contact_apply(ct, state%node_position, state%node_velocity, force, 1.0e-3_rk, &
        int(stage, i8), mod(stage, 2) == 0, wall_time)
    finite = finite .and. all(abs(force) < huge(1.0_rk))
  end do
  call check_true('a global search on the new surfaces', ct%rebuilds > searches)

  ! The owner directory after the refresh.
  call check_true('the directory holds every contact node once', &
      par_sum(size(ct%dir_gid)) == ct%nall)
  call check_true('each entry on the rank mod(global id, ranks)', par_sum(count( &
      modulo(ct%dir_gid, int(par_size(), i8)) /= int(par_rank(), i8))) == 0)
  allocate(named(par_size()), held(par_size()))
  named = 0.0_rk
  do i = 1, size(ct%dir_owner)
    named(ct%dir_owner(i) + 1) = named(ct%dir_owner(i) + 1) + 1.0_rk
  end do
  call par_sum_array(named)
  call check_true('the entries naming each rank number its owned contact nodes', &
      par_sum(merge(0, 1, nint(named(par_rank() + 1)) == ct%nown)) == 0)
  ! Each owned node's entry, on its directory rank (a sum over the ranks of
  ! every owned node's global id against every entry's naming this rank).
  held = 0.0_rk
  do i = 1, size(ct%dir_gid)
    held(ct%dir_owner(i) + 1) = held(ct%dir_owner(i) + 1) + real(ct%dir_gid(i), rk)
  end do
  call par_sum_array(held)
  call check_true('the entries naming each rank hold its owned nodes'' global ids', &
      par_sum(merge(0, 1, nint(held(par_rank() + 1), i8) == &
      sum(ct%all_gid(ct%own_contact)))) == 0)
  call check_true('contact forces finite', par_sum(merge(0, 1, finite)) == 0)
  if (par_rank() == 0) write(output_unit, '(a,i0,a,i0)') 'contact nodes ', ct%nall, &
      ', segments of a ', ct%pairs(1)%all_a%nseg
  call par_finalize()
  call check_summary()
end program test_contact_refresh
