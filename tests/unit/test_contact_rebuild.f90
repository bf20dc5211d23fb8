!> contact_surface_rebuild (through contact_sides' gather) against a brute
!> force on the whole mesh: the exterior faces of the live zones of given
!> blocks, with zones masked at random (the mask set on the owned zones,
!> ghosts from the zone halo), symmetry and rigid-wall faces left out, faces
!> between two blocks interior unless the other block faces the surface.
!> The brute force matches faces by their sorted node ids over the global
!> mesh (no local mesh, no face neighbours). Exact: the same face ids, in
!> the same (ascending) order, with the same nodes, on every rank.
!> Usage: test_contact_rebuild DECK (tests/unit/data/rebuild_blocks.nml).
program test_contact_rebuild
  use, intrinsic :: iso_fortran_env, only: output_unit
  use core_kinds, only: rk, ik, i8
  use core_status, only: status_t
  use core_timer, only: timers_t
  use core_sort, only: sort_order, sort_values
  use parallel_env, only: par_init, par_finalize, par_rank, par_min
  use io_deck, only: config_t, deck_read
  use io_h5, only: h5_library_open
  use mesh_global, only: global_mesh_t
  use mesh_local, only: mesh_t
  use mesh_geometry, only: HEX_FACE_NODES
  use hydro_boundary, only: boundary_t, BC_SYMMETRY, BC_WALL
  use contact_sides, only: side_context_t, block_faces
  use app_setup, only: setup_mesh
  use check, only: check_true, check_summary
  implicit none
  character(len=512) :: deck
  character(len=400) :: msg
  type(config_t) :: config
  type(status_t) :: status
  type(global_mesh_t) :: global
  type(mesh_t) :: mesh
  type(boundary_t) :: bc
  type(timers_t) :: timers
  real(rk), allocatable :: coordinates(:, :)
  type(side_context_t) :: context
  integer(i8), allocatable :: face_key(:, :)
  integer, allocatable :: key_order(:), closed(:, :)
  integer :: ierr, mask, total, dead_faces
  logical :: all_same

  call par_init()
  call get_command_argument(1, deck)
  call h5_library_open(ierr, msg)
  call deck_read(trim(deck), config, status)
  call timers%add('mesh generate')
  call timers%add('dual graph')
  call timers%add('partition')
  call timers%add('migrate')
  call timers%add('halo plans')
  call setup_mesh(config, global, mesh, coordinates, bc, timers, status, whole=.true.)
  call check_true('deck and mesh', status%ok())
  context%block_names = config%blocks(:)%name
  context%closed_sets = pack(config%boundaries(:)%set, config%boundaries(:)%kind == &
      BC_SYMMETRY .or. config%boundaries(:)%kind == BC_WALL)
  call brute_force_setup()

  all_same = .true.
  total = 0
  dead_faces = 0
  do mask = 0, 3
    ! a alone; a facing b; a and b as one surface; c (separate); a and c facing each other
    call compare(mask, [1], [integer ::])
    call compare(mask, [1], [2])
    call compare(mask, [1, 2], [integer ::])
    call compare(mask, [3], [integer ::])
    call compare(mask, [1], [3])
  end do
  call check_true('rebuilt faces equal the brute force (ids, order, nodes) on every rank', &
      par_min(merge(1, 0, all_same)) == 1)
  call check_true('the surfaces are not empty', total > 0)
  call check_true('masked zones open faces that are interior when all are live', dead_faces > 0)
  if (par_rank() == 0) write(output_unit, '(a,i0,a,i0)') 'faces compared ', total, &
      ', of them opened by a masked zone ', dead_faces
  call par_finalize()
  call check_summary()

contains

  !> Live zone by global id: mask 0 keeps all, others drop about a third.
  logical function alive(gid, m)
    integer(i8), intent(in) :: gid
    integer, intent(in) :: m
    alive = m == 0 .or. mod(gid * 7919_i8 + int(m, i8) * 104729_i8, 3_i8) /= 0_i8
  end function alive

  !> Face keys (sorted node ids) of every face of the global mesh, their
  !> order, and the faces of the closed sets.
  subroutine brute_force_setup()
    integer :: z, f, s, j, k
    integer(i8) :: v(4)
    allocate(face_key(4, 6 * global%nzone))
    do z = 1, global%nzone
      do f = 1, 6
        v = int(global%connectivity(HEX_FACE_NODES(:, f), z), i8)
        call sort_values(v)
        face_key(:, 6 * (z - 1) + f) = v
      end do
    end do
    call sort_order(face_key, key_order)
    allocate(closed(6, global%nzone))
    closed = 0
    do j = 1, size(context%closed_sets)
      s = global%find_set(context%closed_sets(j))
      do k = global%set_start(s), global%set_start(s + 1) - 1
        closed(global%set_face(k), global%set_zone(k)) = 1
      end do
    end do
  end subroutine brute_force_setup

  !> The zone across face id (0: none).
  integer function across(id)
    integer, intent(in) :: id
    integer :: lo, hi, mid, q, c
    lo = 1
    hi = size(key_order)
    ! first position of the face's key in the sorted keys
    do while (lo < hi)
      mid = (lo + hi) / 2
      if (less(face_key(:, key_order(mid)), face_key(:, id))) then
        lo = mid + 1
      else
        hi = mid
      end if
    end do
    across = 0
    do q = lo, size(key_order)
      c = key_order(q)
      if (any(face_key(:, c) /= face_key(:, id))) exit
      if (c /= id) across = (c - 1) / 6 + 1
    end do
  end function across

  logical function less(a, b)
    integer(i8), intent(in) :: a(4), b(4)
    integer :: i
    less = .false.
    do i = 1, 4
      if (a(i) /= b(i)) then
        less = a(i) < b(i)
        return
      end if
    end do
  end function less

  subroutine compare(m, blocks, facing)
    integer, intent(in) :: m, blocks(:), facing(:)
    real(rk), allocatable :: flag(:)
    logical, allocatable :: live(:)
    integer(i8), allocatable :: ids(:), want(:)
    integer(ik), allocatable :: nodes(:, :)
    integer :: z, f, n, nb, i
    logical :: exterior, ok
    ! The mask on the owned zones; the ghosts' from the zone halo.
    allocate(flag(mesh%nzone))
    flag = -1.0_rk
    do z = 1, mesh%nzone_owned
      flag(z) = merge(1.0_rk, 0.0_rk, alive(mesh%zone_gid(z), m))
    end do
    call mesh%zone_halo%halo_exchange_scalar(flag)
    live = flag > 0.5_rk
    call block_faces(mesh, live, blocks, facing, context, ids, nodes)
    ! Brute force over the global mesh.
    allocate(want(0))
    do z = 1, global%nzone
      if (.not. alive(int(z, i8), m)) cycle
      if (.not. any(blocks == global%zone_block(z))) cycle
      do f = 1, 6
        if (closed(f, z) == 1) cycle
        nb = across(6 * (z - 1) + f)
        if (nb == 0) then
          exterior = .true.
        else if (.not. alive(int(nb, i8), m)) then
          exterior = .true.
          if (any(blocks == global%zone_block(nb))) dead_faces = dead_faces + 1
        else
          exterior = any(facing == global%zone_block(nb))
        end if
        if (exterior) want = [want, int(6 * (z - 1) + f, i8)]
      end do
    end do
    ok = size(ids) == size(want)
    if (ok) ok = all(ids == want)
    if (ok) then
      do i = 1, size(ids)
        n = int((ids(i) - 1) / 6 + 1)
        f = int(ids(i) - 6 * (n - 1))
        ok = ok .and. all(nodes(:, i) == global%connectivity(HEX_FACE_NODES(:, f), n))
      end do
    end if
    if (.not. ok .and. par_rank() == 0) write(output_unit, '(a,i0,a,*(1x,i0))') 'mask ', m, &
        ' differs for blocks', blocks
    all_same = all_same .and. ok
    total = total + size(want)
  end subroutine compare

end program test_contact_rebuild
